#pragma once
// The subcommands of `wrc study`, one per source file of studies/.

#include <CLI/CLI.hpp>

namespace wrc::cli {

/// Adds `solver` and `tables` (accuracy against cost) to `wrc study`.
void AddCostStudies(CLI::App& study, int* exit_code);

/// Adds `stability` (the solver over the hard cases of contact, gated) to `wrc study`.
void AddStabilityStudy(CLI::App& study, int* exit_code);

/// Adds `dynamics` (a wheelset on table and on solver forces) to `wrc study`.
void AddDynamicsStudy(CLI::App& study, int* exit_code);

/// Adds `paper` (the paper's Figs. 13-16 on the shipped heavy-haul profiles) to `wrc study`.
void AddPaperStudy(CLI::App& study, int* exit_code);

/// Adds `planar` (the planar methods of the paper's Table 1 against the curved reference over
/// a set of profile pairs and poses, Table 3) to `wrc study`.
void AddPlanarStudy(CLI::App& study, int* exit_code);

}  // namespace wrc::cli
