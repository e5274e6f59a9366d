#pragma once
// The FMI 2.0 counterpart of fmi3_importer.h, written from the FMI 2.0.5 standard's C API: the
// unpacked FMU's binaries/linux64 library, its functions bound by name, the value references
// read from a 2.0 modelDescription.xml, and a logger that formats its message as printf does.

#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <stdexcept>
#include <string>

#include "fmu/fmi2_types.h"
#include "tests/fmu/fmi3_importer.h"

namespace wrc::test {

namespace fmi2 = wrc::fmu::fmi2;

inline void Log2ToVector(fmi2::ComponentEnvironment env, fmi2::String, fmi2::Status status,
                         fmi2::String, fmi2::String format, ...) {
  char message[2048];
  va_list args;
  va_start(args, format);
  std::vsnprintf(message, sizeof message, format, args);
  va_end(args);
  static_cast<Log*>(env)->messages.emplace_back(static_cast<fmi3::Status>(status), message);
}

class Fmi2Fmu {
 public:
  using Instantiate = void* (*)(fmi2::String, fmi2::Type, fmi2::String, fmi2::String,
                                const fmi2::CallbackFunctions*, fmi2::Boolean, fmi2::Boolean);
  using Simple = fmi2::Status (*)(void*);
  using Setup = fmi2::Status (*)(void*, fmi2::Boolean, fmi2::Real, fmi2::Real, fmi2::Boolean,
                                 fmi2::Real);
  using GetReal = fmi2::Status (*)(void*, const fmi2::ValueReference[], size_t, fmi2::Real[]);
  using SetReal = fmi2::Status (*)(void*, const fmi2::ValueReference[], size_t, const fmi2::Real[]);
  using GetInteger = fmi2::Status (*)(void*, const fmi2::ValueReference[], size_t, fmi2::Integer[]);
  using DoStep = fmi2::Status (*)(void*, fmi2::Real, fmi2::Real, fmi2::Boolean);

  explicit Fmi2Fmu(const std::filesystem::path& dir) : dir_(dir) {
    std::ifstream in(dir / "modelDescription.xml");
    xml_.assign(std::istreambuf_iterator<char>(in), {});
    std::smatch m;
    if (!std::regex_search(xml_, m, std::regex("guid=\"([^\"]*)\""))) {
      throw std::runtime_error("modelDescription.xml has no guid");
    }
    guid_ = m[1];
    const std::regex variable(R"re(<ScalarVariable name="([^"]+)" valueReference="(\d+)")re");
    for (std::sregex_iterator it(xml_.begin(), xml_.end(), variable), end; it != end; ++it) {
      vr_[(*it)[1]] = static_cast<fmi2::ValueReference>(std::stoul((*it)[2]));
    }
    const auto so = dir / "binaries" / "linux64" / "wrc_wheelset.so";
    library_ = std::make_unique<SharedLibrary>(so);
    instantiate = Bind<Instantiate>("fmi2Instantiate");
    free_instance = Bind<void (*)(void*)>("fmi2FreeInstance");
    setup = Bind<Setup>("fmi2SetupExperiment");
    enter_initialization = Bind<Simple>("fmi2EnterInitializationMode");
    exit_initialization = Bind<Simple>("fmi2ExitInitializationMode");
    terminate = Bind<Simple>("fmi2Terminate");
    get_real = Bind<GetReal>("fmi2GetReal");
    set_real = Bind<SetReal>("fmi2SetReal");
    get_integer = Bind<GetInteger>("fmi2GetInteger");
    do_step = Bind<DoStep>("fmi2DoStep");
  }
  Fmi2Fmu(const Fmi2Fmu&) = delete;
  Fmi2Fmu& operator=(const Fmi2Fmu&) = delete;

  void* Symbol(const char* name) const { return library_->Symbol(name); }
  fmi2::ValueReference Vr(const std::string& name) const { return vr_.at(name); }
  const std::string& guid() const { return guid_; }
  /// The resources folder as a file URI, a space written %20 as an importer writes it.
  std::string resource_uri() const {
    std::string uri = "file://";
    for (const char c : (dir_ / "resources").string())
      uri += c == ' ' ? std::string("%20") : std::string(1, c);
    return uri;
  }

  void* Instantiate2(Log* log, const std::string& guid) {
    callbacks_ = {Log2ToVector, nullptr, nullptr, nullptr, log};
    return instantiate("wheelset", fmi2::kCoSimulation, guid.c_str(), resource_uri().c_str(),
                       &callbacks_, 0, 0);
  }
  double GetFloat64(void* instance, const std::string& name) const {
    const fmi2::ValueReference vr = Vr(name);
    double value = -1.0;
    get_real(instance, &vr, 1, &value);
    return value;
  }
  int SetFloat64(void* instance, const std::string& name, double value) const {
    const fmi2::ValueReference vr = Vr(name);
    return set_real(instance, &vr, 1, &value);
  }
  int Step(void* instance, double time, double step) const {
    return do_step(instance, time, step, 1);
  }

  Instantiate instantiate = nullptr;
  void (*free_instance)(void*) = nullptr;
  Setup setup = nullptr;
  Simple enter_initialization = nullptr, exit_initialization = nullptr, terminate = nullptr;
  GetReal get_real = nullptr;
  SetReal set_real = nullptr;
  GetInteger get_integer = nullptr;
  DoStep do_step = nullptr;

 private:
  template <typename F>
  F Bind(const char* name) const {
    return library_->Bind<F>(name);
  }

  std::filesystem::path dir_;
  std::string xml_, guid_;
  std::map<std::string, fmi2::ValueReference> vr_;
  fmi2::CallbackFunctions callbacks_{};
  std::unique_ptr<SharedLibrary> library_;
};

}  // namespace wrc::test
