#pragma once
// A small FMI 3.0 importer for the tests, written from the standard's C API (FMI 3.0, sections
// 2.2 and 4): it unpacks an .fmu with libzip, reads the value references from
// modelDescription.xml, loads binaries/<platform>/<modelIdentifier>.so with dlopen, binds
// the functions by name and runs the co-simulation calls. It checks what an importer relies
// on: that every function of the interface is exported.

#include <zip.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "fmu/fmi3_types.h"
#include "tests/fmu/shared_library.h"

namespace wrc::test {

namespace fmi3 = wrc::fmu::fmi3;

/// Extracts every file of the zip archive at `archive` into `dir`.
inline void Unzip(const std::filesystem::path& archive, const std::filesystem::path& dir) {
  int error = 0;
  zip_t* z = zip_open(archive.c_str(), ZIP_RDONLY, &error);
  if (z == nullptr) throw std::runtime_error("cannot open " + archive.string());
  for (zip_int64_t i = 0; i < zip_get_num_entries(z, 0); ++i) {
    zip_stat_t st;
    zip_stat_index(z, static_cast<zip_uint64_t>(i), 0, &st);
    const std::filesystem::path out = dir / st.name;
    std::filesystem::create_directories(out.parent_path());
    std::string bytes(st.size, '\0');
    zip_file_t* f = zip_fopen_index(z, static_cast<zip_uint64_t>(i), 0);
    const zip_int64_t got = f != nullptr ? zip_fread(f, bytes.data(), st.size) : -1;
    if (f != nullptr) zip_fclose(f);
    if (got != static_cast<zip_int64_t>(st.size)) {
      zip_close(z);
      throw std::runtime_error("cannot read " + std::string(st.name));
    }
    std::ofstream(out, std::ios::binary) << bytes;
  }
  zip_close(z);
}

/// Messages the FMU logged, with their status.
struct Log {
  std::vector<std::pair<fmi3::Status, std::string>> messages;
  std::string All() const {
    std::string all;
    for (const auto& m : messages) all += m.second + '\n';
    return all;
  }
};

inline void LogToVector(fmi3::InstanceEnvironment env, fmi3::Status status, fmi3::String,
                        fmi3::String message) {
  static_cast<Log*>(env)->messages.emplace_back(status, message);
}

class Fmi3Fmu {
 public:
  using Instantiate = void* (*)(fmi3::String, fmi3::String, fmi3::String, fmi3::Boolean,
                                fmi3::Boolean, fmi3::Boolean, fmi3::Boolean,
                                const fmi3::ValueReference[], size_t, fmi3::InstanceEnvironment,
                                fmi3::LogMessageCallback, fmi3::IntermediateUpdateCallback);
  using Free = void (*)(void*);
  using Simple = fmi3::Status (*)(void*);
  using EnterInit = fmi3::Status (*)(void*, fmi3::Boolean, fmi3::Float64, fmi3::Float64,
                                     fmi3::Boolean, fmi3::Float64);
  template <typename T>
  using Get = fmi3::Status (*)(void*, const fmi3::ValueReference[], size_t, T[], size_t);
  template <typename T>
  using Set = fmi3::Status (*)(void*, const fmi3::ValueReference[], size_t, const T[], size_t);
  using DoStep = fmi3::Status (*)(void*, fmi3::Float64, fmi3::Float64, fmi3::Boolean,
                                  fmi3::Boolean*, fmi3::Boolean*, fmi3::Boolean*, fmi3::Float64*);

  /// `dir` holds the unpacked FMU.
  explicit Fmi3Fmu(const std::filesystem::path& dir) : dir_(dir) {
    std::ifstream in(dir / "modelDescription.xml");
    xml_.assign(std::istreambuf_iterator<char>(in), {});
    identifier_ = Attribute("modelIdentifier");
    token_ = Attribute("instantiationToken");
    const std::regex variable(
        R"re(<(Float64|Int32|String|Enumeration) name="([^"]+)" valueReference="(\d+)")re");
    for (std::sregex_iterator it(xml_.begin(), xml_.end(), variable), end; it != end; ++it) {
      vr_[(*it)[2]] = static_cast<fmi3::ValueReference>(std::stoul((*it)[3]));
    }
    const auto so = dir / "binaries" / "x86_64-linux" / (identifier_ + ".so");
    library_ = std::make_unique<SharedLibrary>(so);
    instantiate = Bind<Instantiate>("fmi3InstantiateCoSimulation");
    free_instance = Bind<Free>("fmi3FreeInstance");
    enter_initialization = Bind<EnterInit>("fmi3EnterInitializationMode");
    exit_initialization = Bind<Simple>("fmi3ExitInitializationMode");
    terminate = Bind<Simple>("fmi3Terminate");
    reset = Bind<Simple>("fmi3Reset");
    get_float64 = Bind<Get<double>>("fmi3GetFloat64");
    set_float64 = Bind<Set<double>>("fmi3SetFloat64");
    get_int32 = Bind<Get<std::int32_t>>("fmi3GetInt32");
    set_int64 = Bind<Set<std::int64_t>>("fmi3SetInt64");
    set_string = Bind<Set<fmi3::String>>("fmi3SetString");
    do_step = Bind<DoStep>("fmi3DoStep");
  }
  Fmi3Fmu(const Fmi3Fmu&) = delete;
  Fmi3Fmu& operator=(const Fmi3Fmu&) = delete;

  void* Symbol(const char* name) const { return library_->Symbol(name); }
  fmi3::ValueReference Vr(const std::string& name) const { return vr_.at(name); }
  const std::string& token() const { return token_; }
  std::string resources() const { return (dir_ / "resources").string() + "/"; }
  const std::string& xml() const { return xml_; }

  void* Instantiate3(Log* log, const std::string& token) const {
    return instantiate("wheelset", token.c_str(), resources().c_str(), false, false, false, false,
                       nullptr, 0, log, LogToVector, nullptr);
  }

  double GetFloat64(void* instance, const std::string& name, fmi3::Status* status = nullptr) const {
    const fmi3::ValueReference vr = Vr(name);
    double value = -1.0;
    const fmi3::Status s = get_float64(instance, &vr, 1, &value, 1);
    if (status != nullptr) *status = s;
    return value;
  }
  fmi3::Status SetFloat64(void* instance, const std::string& name, double value) const {
    const fmi3::ValueReference vr = Vr(name);
    return set_float64(instance, &vr, 1, &value, 1);
  }
  /// fmi3DoStep, checking what a step of this FMU must report besides its status.
  int Step(void* instance, double time, double step) const {
    fmi3::Boolean event = true, terminate = true, early = true;
    double reached = 0.0;
    const fmi3::Status status =
        do_step(instance, time, step, true, &event, &terminate, &early, &reached);
    if (event || terminate || early || (status == fmi3::kOK && reached != time + step)) return -1;
    return status;
  }

  Instantiate instantiate = nullptr;
  Free free_instance = nullptr;
  EnterInit enter_initialization = nullptr;
  Simple exit_initialization = nullptr, terminate = nullptr, reset = nullptr;
  Get<double> get_float64 = nullptr;
  Set<double> set_float64 = nullptr;
  Get<std::int32_t> get_int32 = nullptr;
  Set<std::int64_t> set_int64 = nullptr;
  Set<fmi3::String> set_string = nullptr;
  DoStep do_step = nullptr;

 private:
  std::string Attribute(const std::string& name) const {
    std::smatch m;
    if (!std::regex_search(xml_, m, std::regex(name + "=\"([^\"]*)\""))) {
      throw std::runtime_error("modelDescription.xml has no " + name);
    }
    return m[1];
  }
  template <typename F>
  F Bind(const char* name) const {
    return library_->Bind<F>(name);
  }

  std::filesystem::path dir_;
  std::string xml_, identifier_, token_;
  std::map<std::string, fmi3::ValueReference> vr_;
  std::unique_ptr<SharedLibrary> library_;
};

}  // namespace wrc::test
