#pragma once
// SIGINT/SIGTERM during `wrc generate`: the first signal asks the run to stop cleanly (workers
// take no new points, the journal is flushed); the handler then reverts to the default action,
// so a second Ctrl-C ends the process at once (finished points are in the journal either way).

namespace wrc::gen {

/// Installs the handlers for its lifetime and restores the previous ones afterwards.
class InterruptHandlers {
 public:
  InterruptHandlers();
  ~InterruptHandlers();
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;
};

/// True once SIGINT or SIGTERM arrived while handlers were installed.
bool InterruptRequested();

/// Clears the flag (a new run starts uninterrupted).
void ClearInterrupt();

}  // namespace wrc::gen
