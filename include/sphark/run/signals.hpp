#pragma once
// SIGINT / SIGTERM as a polite stop request: the handler only records the signal number; run
// loops poll stop_requested() between Stepper::advance() calls, write a checkpoint and exit.
// No work (no I/O, no allocation) happens inside the handler.
namespace sphark {

// Installs the handler for SIGINT and SIGTERM (idempotent).
void install_stop_handlers();
// 0 while no stop was requested, else the number of the first signal received.
int stop_requested();
// Clears the request (tests; a run that handled it).
void clear_stop_request();

}  // namespace sphark
