#include "wrc/generator/interrupt.h"

#include <atomic>
#include <csignal>

namespace wrc::gen {
namespace {

// Lock-free, so that setting it in a signal handler is safe.
std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);

struct sigaction g_previous_int;
struct sigaction g_previous_term;

extern "C" void OnInterrupt(int) { g_interrupted.store(true, std::memory_order_relaxed); }

}  // namespace

InterruptHandlers::InterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = OnInterrupt;
  sigemptyset(&action.sa_mask);
  // One-shot: the handler resets to the default, so a second signal terminates at once.
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptHandlers::~InterruptHandlers() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

bool InterruptRequested() { return g_interrupted.load(std::memory_order_relaxed); }

void ClearInterrupt() { g_interrupted.store(false, std::memory_order_relaxed); }

}  // namespace wrc::gen
