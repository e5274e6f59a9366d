#pragma once
/// @file interrupt.h
/// SIGINT/SIGTERM during a long run (`wrc generate`, `wrc verify`): the first signal asks the
/// run to stop cleanly (workers take no new points; the generator flushes its journal); the
/// handler then reverts to the default action, so a second Ctrl-C ends the process at once.
/// Part of the generator library.

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
