#pragma once
/// @file table_schema.h
/// The layout of a wrc table (docs/reference/table-layout.md), defined once: the generator
/// writes it, the runtime and `wrc info` read it, and the tests forge tables with it. Every
/// name a writer or reader uses for a group, dataset or attribute of a table is here.

#include <cstdint>
#include <string>
#include <vector>

namespace wrc::schema {

/// Value of the root attribute `format`, and the version this build writes and reads.
inline constexpr const char* kFormatName = "wrc-table";
inline constexpr std::int64_t kFormatVersion = 1;

// Root attributes.
inline constexpr const char* kFormat = "format";
inline constexpr const char* kFormatVersionAttribute = "format_version";
inline constexpr const char* kWrcVersion = "wrc_version";
inline constexpr const char* kCreated = "created";
inline constexpr const char* kScene = "scene";
inline constexpr const char* kRailProfileSha256 = "rail_profile_sha256";
inline constexpr const char* kWheelProfileSha256 = "wheel_profile_sha256";
inline constexpr const char* kZWarmStart = "z_warm_start";
inline constexpr const char* kWarningsCount = "warnings_count";
inline constexpr const char* kRefineTarget = "refine_target";
inline constexpr const char* kRefinePasses = "refine_passes";
inline constexpr const char* kRefineStop = "refine_stop";
inline constexpr const char* kRefineEstimatedError = "refine_estimated_error";
/// JSON array: the CPU seconds of the generating process at the end of each pass, a
/// measurement (like /solve_time_s), so apart from the reproducible refinement record.
inline constexpr const char* kRefineCpuSeconds = "refine_cpu_seconds";

// Root float64 attributes: the fixed state a table was made at, which the runtime's wheelset
// API needs (wrc_wheelset_create). Written by every table since they were introduced; tables
// written before carry only the scene text, from which the runtime reads the same values.
inline constexpr const char* kWheelsetVelocity = "wheelset_velocity";             ///< V, mm/s
inline constexpr const char* kWheelsetNominalRadius = "wheelset_nominal_radius";  ///< r0, mm
/// The lateral distance of the wheel profile's origin from the wheelset centre, mm
/// (flange_back_distance / 2 − flange_back_position): the lever of the yaw rate's creepage.
inline constexpr const char* kWheelProfileOffset = "wheel_profile_offset";
/// Prefix of one attribute per state quantity of wrc/quantities.h (`fixed_y`, `fixed_fz`, …):
/// its value in the table's scene, NaN where the table does not fix it (an axis, z with a
/// prescribed fz, friction that varies with the contact angle).
inline constexpr const char* kFixedPrefix = "fixed_";
/// Root string attribute: "left" or "right", the wheel the table was made for.
inline constexpr const char* kWheelsetSide = "wheelset_side";

// Groups and datasets.
inline constexpr const char* kAxes = "axes";               ///< group: one dataset per axis
inline constexpr const char* kOutputs = "outputs";         ///< group: one dataset per output
inline constexpr const char* kStatus = "status";           ///< int8 per point, PointStatus
inline constexpr const char* kSolveTime = "solve_time_s";  ///< float32 per point
inline constexpr const char* kProfiles = "profiles";       ///< group: the profile files' bytes
inline constexpr const char* kRailProfile = "rail";
inline constexpr const char* kWheelProfile = "wheel";
inline constexpr const char* kErrors = "errors";         ///< group: why points failed
inline constexpr const char* kErrorPoint = "point";      ///< int64, flat row-major index
inline constexpr const char* kErrorMessage = "message";  ///< strings

// Attributes of groups and datasets.
inline constexpr const char* kOrder = "order";  ///< of axes and outputs: names in order
inline constexpr const char* kUnit = "unit";
inline constexpr const char* kDimensions = "dimensions";  ///< of a gridded dataset: the axes
inline constexpr const char* kMeaning = "meaning";
inline constexpr const char* kProfileName = "name";  ///< of a profile: its file name

/// The values of `status`.
enum class StoredStatus : std::int8_t { kOk = 0, kNoContact = 1, kNotConverged = 2, kError = 3 };
inline constexpr int kStoredStatusCount = 4;
inline constexpr const char* kStatusMeaning = "0 ok, 1 no contact, 2 not converged, 3 error";

}  // namespace wrc::schema
