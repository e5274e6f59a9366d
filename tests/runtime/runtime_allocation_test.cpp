// Evaluation must not allocate. This test binary replaces the global operator new/delete and
// interposes malloc and friends (glibc: the executable's definitions take precedence over
// libc's for every library in the process) with versions that count calls made by threads that
// switched counting on.

#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "tests/runtime/table_writer.h"
#include "tests/runtime/wheelset_table.h"
#include "wrc/runtime.h"
#include "wrc/runtime.hpp"

// AddressSanitizer interposes malloc itself; bypassing it would break its bookkeeping. Under
// ASan only operator new is counted.
#if defined(__SANITIZE_ADDRESS__)
#define WRC_TEST_INTERPOSE_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define WRC_TEST_INTERPOSE_MALLOC 0
#endif
#endif
#ifndef WRC_TEST_INTERPOSE_MALLOC
#define WRC_TEST_INTERPOSE_MALLOC 1
#endif

namespace {

std::atomic<long> g_allocations{0};
thread_local bool t_counting = false;

void NoteAllocation() {
  if (t_counting) g_allocations.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

#if WRC_TEST_INTERPOSE_MALLOC
extern "C" {
// glibc's internal entry points of its allocator.
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);

void* malloc(std::size_t size) noexcept {
  NoteAllocation();
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  NoteAllocation();
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) noexcept {
  NoteAllocation();
  return __libc_realloc(pointer, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  NoteAllocation();
  return __libc_memalign(alignment, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  NoteAllocation();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** pointer, std::size_t alignment, std::size_t size) noexcept {
  NoteAllocation();
  *pointer = __libc_memalign(alignment, size);
  return *pointer != nullptr ? 0 : ENOMEM;
}
}  // extern "C"
#endif

// The replacements pair operator new with malloc and operator delete with free, which GCC's
// -Wmismatched-new-delete cannot see once it inlines library code around them.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t size) {
  NoteAllocation();
  if (void* pointer = std::malloc(size == 0 ? 1 : size)) return pointer;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  NoteAllocation();
  if (void* pointer = std::malloc(size == 0 ? 1 : size)) return pointer;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  NoteAllocation();
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  NoteAllocation();
  return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* pointer) noexcept { std::free(pointer); }
void operator delete[](void* pointer) noexcept { std::free(pointer); }
void operator delete(void* pointer, std::size_t) noexcept { std::free(pointer); }
void operator delete[](void* pointer, std::size_t) noexcept { std::free(pointer); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace {

// Counts allocations of the calling thread while alive.
class AllocationCounter {
 public:
  AllocationCounter() : start_(g_allocations.load()) { t_counting = true; }
  ~AllocationCounter() { t_counting = false; }
  long count() const { return g_allocations.load() - start_; }

 private:
  long start_;
};

// Keeps the compiler from eliding a new/delete or malloc/free pair.
void* volatile g_sink = nullptr;

TEST(RuntimeAllocation, CounterSeesAllocations) {
  long count = 0;
  {
    AllocationCounter counter;
    int* number = new int(3);
    g_sink = number;
    delete number;
    void* block = std::malloc(64);
    g_sink = block;
    std::free(block);
    std::vector<double> vector(100);
    g_sink = vector.data();
    count = counter.count();
  }
  // new + malloc + vector (whose new calls malloc again when malloc is interposed).
  EXPECT_GE(count, WRC_TEST_INTERPOSE_MALLOC ? 4 : 2);
}

// Every kind of call on both modes, with the node data read as `storage`.
void ExpectEvaluationDoesNotAllocate(int storage) {
  wrc::test::ScratchFile scratch("allocation");
  wrc::test::TableContent content;
  content.axes = wrc::test::WheelsetAxes(41);
  content.outputs = {"fx", "fy", "fz", "mx", "my", "mz", "pmax", "contact_y", "contact_angle"};
  content.function = [](int k, const std::vector<double>& x) {
    return std::sin(0.3 * x[0] + k) + 100.0 * x[1] + std::cos(300.0 * x[3]) * x[2];
  };
  content.status = [](const std::vector<double>& x) -> std::int8_t { return x[0] == 5.0 ? 1 : 0; };
  wrc::test::WriteTable(scratch.path(), content);

  wrc_table* linear = nullptr;
  wrc_table* cubic = nullptr;
  ASSERT_EQ(wrc_table_open(scratch.path().c_str(), &linear), 0) << wrc_last_error();
  ASSERT_EQ(wrc_table_open(scratch.path().c_str(), &cubic), 0) << wrc_last_error();
  ASSERT_EQ(wrc_table_set_interpolation(cubic, WRC_INTERP_CUBIC), 0);
  ASSERT_EQ(wrc_table_set_storage(linear, storage), 0);
  ASSERT_EQ(wrc_table_set_storage(cubic, storage), 0);
  wrc::Table wrapped(scratch.path());
  wrapped.set_storage(static_cast<wrc::Storage>(storage));

  // Points inside, outside (clamped) and NaN (error path), prepared before counting.
  std::mt19937 random(31);
  std::uniform_real_distribution<double> unit(-1.3, 1.3);
  std::vector<double> points;
  for (int i = 0; i < 1000; ++i) {
    points.push_back(10.0 * unit(random));
    points.push_back(0.002 * unit(random));
    points.push_back(0.01 * unit(random));
    points.push_back(i % 100 == 0 ? std::nan("") : 0.01 * unit(random));
  }
  std::vector<double> out(9);
  std::vector<double> d_out(9 * 4);
  int results[4] = {0, 0, 0, 0};  // Count of errors per call kind, to check the paths ran.
  long count = 0;
  {
    AllocationCounter counter;
    for (std::size_t i = 0; i < points.size(); i += 4) {
      const double* point = &points[i];
      results[0] += wrc_table_eval(linear, point, out.data()) < 0;
      results[1] += wrc_table_eval_deriv(linear, point, out.data(), d_out.data()) < 0;
      results[2] += wrc_table_eval(cubic, point, out.data()) < 0;
      results[3] += wrc_table_eval_deriv(cubic, point, out.data(), d_out.data()) < 0;
      if (!std::isnan(point[3])) wrapped.eval(point, out.data(), d_out.data());
      g_sink = const_cast<char*>(wrc_last_error());
    }
    count = counter.count();
  }
  EXPECT_EQ(count, 0);
  for (int errors : results) EXPECT_EQ(errors, 10);  // The NaN points took the error path.
  wrc_table_close(linear);
  wrc_table_close(cubic);
}

TEST(RuntimeAllocation, EvaluationDoesNotAllocate) {
  ExpectEvaluationDoesNotAllocate(WRC_STORAGE_FLOAT64);
}

TEST(RuntimeAllocation, EvaluationFromFloat32StorageDoesNotAllocate) {
  ExpectEvaluationDoesNotAllocate(WRC_STORAGE_FLOAT32);
}

// The cubic node data are built when a handle is switched to cubic mode (that call may allocate,
// as documented in runtime.h); from then on cubic evaluation allocates nothing, on every path
// (values, derivatives, clamped points, a cell with a failed node stored as NaN taking the
// valid-corner fallback, a cell whose nodes all failed giving WRC_ERR_NO_DATA, NaN input), and
// switching modes back and forth reuses the data.
TEST(RuntimeAllocation, CubicEvaluationAfterAModeSwitchDoesNotAllocate) {
  wrc::test::ScratchFile scratch("allocation-switch");
  wrc::test::TableContent content;
  content.axes = wrc::test::WheelsetAxes(21);
  content.outputs = {"fx", "fy", "fz", "mx", "my", "mz"};
  // One failed node, and every node at y >= 9: the cells beyond y = 9 have no valid corner.
  const auto failed = [](const std::vector<double>& x) {
    return (x[0] == 5.0 && x[3] == 0.0) || x[0] >= 9.0;
  };
  content.function = [&](int k, const std::vector<double>& x) {
    if (failed(x)) return std::nan("");
    return std::sin(0.3 * x[0] + k) + 100.0 * x[1] + std::cos(300.0 * x[3]) * x[2];
  };
  content.status = [&](const std::vector<double>& x) -> std::int8_t { return failed(x) ? 2 : 0; };
  wrc::test::WriteTable(scratch.path(), content);

  std::mt19937 random(37);
  std::uniform_real_distribution<double> unit(-1.2, 1.2);  // Some points clamped.
  std::vector<double> points;
  for (int i = 0; i < 500; ++i) {
    points.push_back(10.0 * unit(random));
    points.push_back(0.002 * unit(random));
    points.push_back(0.01 * unit(random));
    points.push_back(i % 50 == 0 ? std::nan("") : 0.01 * unit(random));
  }
  points.insert(points.end(), {5.0, 0.0, 0.0, 0.001});  // Next to the failed node: fallback.
  points.insert(points.end(), {9.5, 0.0, 0.0, 0.001});  // In a cell that failed entirely.
  std::vector<double> out(6);
  std::vector<double> d_out(6 * 4);
  // Evaluates every point with and without derivatives; returns the allocations made and
  // counts the results that were errors.
  const auto evaluate_all = [&](const wrc_table* table, int* errors) {
    AllocationCounter counter;
    for (std::size_t i = 0; i < points.size(); i += 4) {
      *errors += wrc_table_eval(table, &points[i], out.data()) < 0;
      *errors += wrc_table_eval_deriv(table, &points[i], out.data(), d_out.data()) < 0;
      g_sink = const_cast<char*>(wrc_last_error());
    }
    return counter.count();
  };

  wrc_table* table = nullptr;
  ASSERT_EQ(wrc_table_open(scratch.path().c_str(), &table), 0) << wrc_last_error();
  int errors = 0;
  EXPECT_EQ(evaluate_all(table, &errors), 0);  // Linear first.
  const int linear_errors = errors;
  EXPECT_GE(errors, 2 * 10 + 2);  // NaN inputs; points in cells that failed entirely.
  ASSERT_EQ(wrc_table_set_interpolation(table, WRC_INTERP_CUBIC), 0);  // Builds: may allocate.
  errors = 0;
  EXPECT_EQ(evaluate_all(table, &errors), 0);
  EXPECT_EQ(errors, linear_errors);  // Cubic slopes skip the NaN node: the same cells fail.
  long switches = 0;
  {
    AllocationCounter counter;
    EXPECT_EQ(wrc_table_set_interpolation(table, WRC_INTERP_LINEAR), 0);
    EXPECT_EQ(wrc_table_set_interpolation(table, WRC_INTERP_CUBIC), 0);
    switches = counter.count();
  }
  EXPECT_EQ(switches, 0);  // The cubic data are kept.
  errors = 0;
  EXPECT_EQ(evaluate_all(table, &errors), 0);
  wrc_table_close(table);

  // The C++ layer, switched to cubic after construction (try_eval: eval would throw, and
  // allocate the exception, on the error points).
  wrc::Table wrapped(scratch.path());
  wrapped.set_interpolation(wrc::Interpolation::kCubic);
  long count = 0;
  errors = 0;
  {
    AllocationCounter counter;
    for (std::size_t i = 0; i < points.size(); i += 4) {
      errors += wrapped.try_eval(&points[i], out.data(), d_out.data()) < 0;
      errors += wrapped.try_eval(&points[i], out.data()) < 0;
    }
    count = counter.count();
  }
  EXPECT_EQ(count, 0);
  EXPECT_EQ(errors, linear_errors);
}

}  // namespace

// The wheelset API evaluates two tables per call and allocates nothing either, on the
// ordinary, the clamped and the error path.
TEST(RuntimeAllocation, WheelsetEvaluationDoesNotAllocate) {
  wrc::test::ScratchFile scratch("allocation-wheelset");
  wrc::test::WriteWheelsetTable(scratch.path());
  const wrc::Table table(scratch.path());
  const wrc::WheelsetTable wheelset(table);
  std::vector<wrc::WheelsetTable::State> states(300);
  for (std::size_t i = 0; i < states.size(); ++i) {
    states[i].y = 0.1 * static_cast<double>(i) - 15.0;  // partly beyond the y axis
    states[i].velocity = 20000.0 + static_cast<double>(i);
    states[i].omega = i % 100 == 0 ? std::nan("") : -states[i].velocity / 460.0;
  }
  int errors = 0;
  long count = 0;
  {
    AllocationCounter counter;
    for (const auto& state : states) {
      wrc_wheelset_result result;
      errors += wheelset.try_eval(state, result) < 0;
      g_sink = const_cast<char*>(wrc_last_error());
    }
    count = counter.count();
  }
  EXPECT_EQ(count, 0);
  EXPECT_EQ(errors, 3);
}
