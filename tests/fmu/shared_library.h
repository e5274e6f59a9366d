#pragma once
// A shared library opened with dlopen (RTLD_LOCAL: its symbols stay its own) and closed with
// the object; functions bound by name, a missing one an error naming it.

#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace wrc::test {

class SharedLibrary {
 public:
  explicit SharedLibrary(const std::filesystem::path& path)
      : handle_(dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
    if (handle_ == nullptr) throw std::runtime_error(std::string("dlopen: ") + dlerror());
  }
  ~SharedLibrary() { dlclose(handle_); }
  SharedLibrary(const SharedLibrary&) = delete;
  SharedLibrary& operator=(const SharedLibrary&) = delete;

  void* Symbol(const char* name) const { return dlsym(handle_, name); }
  template <typename F>
  F Bind(const char* name) const {
    void* symbol = Symbol(name);
    if (symbol == nullptr) throw std::runtime_error(std::string("not exported: ") + name);
    return reinterpret_cast<F>(symbol);
  }

 private:
  void* handle_;
};

}  // namespace wrc::test
