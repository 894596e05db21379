// libFuzzer harness: any bytes as a deck. A deck may be refused (InputError, exit 2 in `peridot`) or accepted
// and set up (exit 0 of `peridot check`); anything else (a crash, a sanitizer report, another exception, a
// hang) is a bug. The set-up is what `peridot check` does: parse and validate, then build the points, bonds,
// loads and models, within a small memory limit so that each input takes milliseconds.
#include <cstddef>
#include <cstdint>
#include <string>

#include "peridot/core/error.hpp"
#include "peridot/deck/deck.hpp"
#include "peridot/solvers/runner.hpp"
#include "peridot/solvers/simulation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Relative file names (points_file) resolve in a folder that does not exist: they are "not found".
    peridot::Problem problem = peridot::parse_deck(text, "fuzz.yaml", "/nonexistent/peridot-fuzz");
    problem.memory_limit = 4 << 20;
    const peridot::Simulation simulation(problem);
    (void)peridot::describe_setup(simulation);
  } catch (const peridot::InputError&) {
    // refused with positions: what a bad deck should get
  }
  return 0;
}
