#include "crash_report.hpp"

#include <execinfo.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstring>

namespace pena::services {
namespace {

char g_program[64] = "pena";  // copied in: the handler may run after main returned

// Only async-signal-safe calls from here on: write(2), backtrace_symbols_fd, signal, raise.
void WriteText(const char* text) {
  const ssize_t ignored = write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

extern "C" void OnFatalSignal(int signal_number) {
  WriteText(g_program);
  WriteText(": fatal signal ");
  const char* name = strsignal(signal_number);  // not listed as safe, but reads a static table
  WriteText(name != nullptr ? name : "?");
  WriteText("; backtrace (innermost first):\n");
  void* frames[64];
  const int count = backtrace(frames, 64);
  backtrace_symbols_fd(frames, count, STDERR_FILENO);
  // Die of the same signal, as without this handler.
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

}  // namespace

void InstallCrashReport(const std::string& program) {
  const std::size_t length = std::min(program.size(), sizeof(g_program) - 1);
  std::memcpy(g_program, program.data(), length);
  g_program[length] = '\0';
  // backtrace() loads libgcc on its first call, which is not safe inside the handler: call it
  // once here.
  void* warm[1];
  (void)backtrace(warm, 1);
  for (const int signal_number : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) {
    std::signal(signal_number, OnFatalSignal);
  }
}

}  // namespace pena::services
