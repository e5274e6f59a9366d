#pragma once
// What the FMI functions of both versions do at the C boundary: run a body on a live instance
// with no exception escaping (logged, and returned as an error; as fatal when memory ran out),
// and apply a get or set to each value reference in turn. Statuses are FMI 3.0's; FMI 2.0
// numbers OK to Fatal alike and casts them.

#include <cstddef>
#include <cstdint>
#include <exception>
#include <new>
#include <string>

#include "fmu/fmi3_types.h"
#include "fmu/instance.h"

namespace wrc::fmu {

template <typename Body>
fmi3::Status Guard(void* instance, const char* function, Body&& body) {
  if (instance == nullptr) return fmi3::kError;
  auto& i = *static_cast<Instance*>(instance);
  try {
    return body(i);
  } catch (const std::bad_alloc&) {
    i.Refuse(function, "out of memory");
    return fmi3::kFatal;
  } catch (const std::exception& e) {
    return i.Refuse(function, e.what());
  }
}

/// A function of an interface or capability the FMU does not declare.
inline fmi3::Status Unsupported(void* instance, const char* function, const char* why) {
  return Guard(instance, function, [&](Instance& i) {
    return i.Refuse(function, std::string("not provided: ") + why);
  });
}

/// access(instance, vr, k) for each of the n value references; the first refusal stops.
template <typename Reference, typename Access>
fmi3::Status Each(void* instance, const char* function, const Reference vrs[], std::size_t n,
                  Access&& access) {
  return Guard(instance, function, [&](Instance& i) {
    if (n > 0 && vrs == nullptr) return i.Refuse(function, "NULL value references");
    fmi3::Status worst = fmi3::kOK;
    for (std::size_t k = 0; k < n; ++k) {
      const fmi3::Status s = access(i, static_cast<std::uint32_t>(vrs[k]), k);
      if (s > worst) worst = s;
      if (s >= fmi3::kError) break;
    }
    return worst;
  });
}

/// Types the FMU has no variables of: any reference is refused, none is fine.
inline fmi3::Status NoVariablesOfType(void* instance, const char* function, std::size_t n) {
  return Guard(instance, function, [&](Instance& i) {
    return n == 0 ? fmi3::kOK : i.Refuse(function, "the FMU has no variables of this type");
  });
}

}  // namespace wrc::fmu
