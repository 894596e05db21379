// peridot: the command-line program.
//   peridot run deck.yaml      run a deck (exit 2: bad deck, nothing written; exit 3: numerical failure;
//                              128 + N: stopped by signal N (SIGINT, SIGTERM, SIGUSR1) after a step)
//   peridot run deck.yaml --restart output/checkpoint_N.nc   continue a run from its checkpoint, bitwise
//   peridot check deck.yaml    validate a deck and print what the run would be, without running it
//   peridot info [--markdown]  every model, key, unit and default, from the schema the parser uses
//   peridot info --model NAME [--markdown]  the documentation page of a material model
//   peridot import-peridigm deck.yaml|deck.xml [-o peridot_deck.yaml]  translate a Peridigm deck, then check it
#include <omp.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "peridot/output/exodus_pieces.hpp"
#include "peridot/core/simd.hpp"
#include "peridot/deck/deck.hpp"
#include "peridot/deck/model_schema.hpp"
#include "peridot/deck/peridigm_import.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/solvers/checkpoint.hpp"
#include "peridot/solvers/runner.hpp"
#include "peridot/solvers/simulation.hpp"

namespace {

constexpr int exit_input_error = 2;
constexpr int exit_numerical_error = 3;

int report(const peridot::InputError& e) {
  // Every rank finds the same deck errors; one reports them.
  if (!peridot::Communicator::world().is_root()) return exit_input_error;
  for (const peridot::Diagnostic& d : e.diagnostics()) std::cerr << d.str() << '\n';
  std::cerr << e.diagnostics().size() << (e.diagnostics().size() == 1 ? " error" : " errors")
            << "; nothing was run or written\n";
  return exit_input_error;
}

/// import-peridigm: translate (a deck that cannot be translated: exit 2, nothing written), write the deck and the
/// files it names, then check it as `peridot check` does. A translation that does not check keeps its files for
/// editing and exits 2 with the errors at their lines of the translated deck.
int import_peridigm(const std::string& deck, std::string output, bool root) {
  if (!root) return 0;
  if (output.empty()) {
    std::filesystem::path p(deck);
    output = (p.parent_path() / (p.stem().string() + ".peridot.yaml")).string();
  }
  const peridot::PeridigmImport result = peridot::import_peridigm(deck, output);
  for (const auto& [path, text] : result.files) peridot::write_file_atomically(path, text);
  peridot::write_file_atomically(output, result.deck);
  for (const std::string& n : result.notes) std::cerr << "note: " << n << '\n';
  std::cout << "wrote " << output;
  for (const auto& file : result.files) std::cout << ", " << std::filesystem::path(file.first).filename().string();
  std::cout << '\n';
  try {
    const peridot::Problem problem = peridot::load_deck(output);
    peridot::Simulation simulation(problem, peridot::Communicator());
    std::cout << output << ": valid\n" << peridot::describe_setup(simulation);
  } catch (const peridot::InputError& e) {
    std::cerr << "the translated deck does not check; it is kept for editing:\n";
    return report(e);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Under mpirun (or srun) each process is one rank of a distributed run; started directly, one rank
  // without MPI (parallel/communicator.hpp).
  peridot::MpiSession mpi(argc, argv);
  const bool root = peridot::Communicator::world().is_root();
  CLI::App app{"Peridot: peridynamic solid mechanics and fracture"};
  app.require_subcommand(1);
  std::string deck;
  int threads = 0;
  bool quiet = false, markdown = false;
  std::string output_dir, model, restart;

  // More threads than a few per core only slows a run down; far more exhausts the machine.
  const int max_threads = 8 * omp_get_num_procs();
  const auto thread_count = CLI::Range(1, max_threads);
  CLI::App* run = app.add_subcommand("run", "run a deck");
  run->add_option("deck", deck, "the YAML deck")->required();
  run->add_option("-t,--threads", threads, "OpenMP threads (default: OMP_NUM_THREADS or all cores)")->check(thread_count);
  run->add_flag("-q,--quiet", quiet, "no progress line and no log on standard output");
  run->add_option("-o,--output-dir", output_dir, "write the outputs here instead of the deck's output.directory");
  run->add_option("--restart", restart,
                  "continue from this checkpoint (output.checkpoint) of the same deck; the end time, step count and "
                  "output settings may differ");

  CLI::App* check = app.add_subcommand("check", "validate a deck and describe the run without running it");
  check->add_option("deck", deck, "the YAML deck")->required();
  check->add_option("-t,--threads", threads, "OpenMP threads")->check(thread_count);
  std::uint64_t max_memory = 0;
  for (CLI::App* command : {run, check})
    command->add_option("--max-memory", max_memory, "refuse decks whose points and bonds need more (4GiB, 500MB; default: the machine's memory)")
        ->transform(CLI::AsSizeValue(false));

  std::string translated;
  CLI::App* import = app.add_subcommand("import-peridigm", "translate a Peridigm deck (YAML or XML) into a Peridot deck and check it");
  import->add_option("deck", deck, "the Peridigm deck (.yaml or .xml)")->required();
  import->add_option("-o,--output", translated, "the Peridot deck to write (default: DECK.peridot.yaml beside the Peridigm deck)");

  std::string pieces, joined;
  CLI::App* join = app.add_subcommand("join", "merge the Exodus pieces of a distributed run (NAME.N.0 … NAME.N.N-1) into one file, "
                                              "the file a serial run writes");
  join->add_option("results", pieces, "the Exodus file the pieces are of, e.g. out/results.e for out/results.e.4.*")->required();
  join->add_option("-o,--output", joined, "the file to write (default: the name the pieces are of)");

  CLI::App* info = app.add_subcommand("info", "list every model, key, unit and default");
  info->add_flag("--markdown", markdown, "print Markdown: docs/deck.md, or docs/models/NAME.md with --model");
  const std::vector<std::string_view> models = peridot::model_names();
  info->add_option("--model", model, "print the documentation page of this material model")
      ->check(CLI::IsMember(std::vector<std::string>(models.begin(), models.end())));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help is a "parse error" that succeeds; every real one is a usage error, reported like a deck's.
    return app.exit(e) == 0 ? 0 : exit_input_error;
  }
  if (threads > 0) omp_set_num_threads(threads);
  // Several ranks on one machine share its cores: one thread per rank unless told otherwise.
  else if (!peridot::Communicator::world().serial() && !std::getenv("OMP_NUM_THREADS")) omp_set_num_threads(1);

  // PERIDOT_SIMD (core/simd.hpp) is checked before anything runs: a target this CPU lacks is a usage error.
  try {
    peridot::simd::apply_environment();
  } catch (const std::invalid_argument& e) {
    if (root) std::cerr << "error: " << e.what() << '\n';
    return exit_input_error;
  }

  try {
    if (info->parsed()) {
      if (!root) return 0;
      if (model.empty() && !markdown) std::cout << "SIMD target of the bond loops: " << peridot::simd::describe() << "\n\n";
      if (model.empty()) peridot::print_schema(std::cout, markdown);
      else peridot::print_model_page(std::cout, *peridot::find_model(model), markdown);
      return 0;
    }
    if (import->parsed()) return import_peridigm(deck, translated, root);
    if (join->parsed()) {
      if (!root) return 0;
      try {
        const int frames = peridot::join_exodus(pieces, joined.empty() ? pieces : joined);
        std::cout << (joined.empty() ? pieces : joined) << ": " << frames << " frame" << (frames == 1 ? "" : "s") << " of "
                  << peridot::piece_paths(pieces).size() << " pieces\n";
        return 0;
      } catch (const std::runtime_error& e) {
        std::cerr << "error: peridot join: " << e.what() << '\n';
        return exit_input_error;
      }
    }
    peridot::Problem problem = peridot::load_deck(deck);
    problem.memory_limit = static_cast<double>(max_memory);
    if (!output_dir.empty()) problem.output.directory = std::filesystem::absolute(output_dir).string();
    if (root)
      for (const peridot::Diagnostic& w : problem.warnings) std::cerr << w.str() << '\n';
    if (check->parsed()) {
      peridot::Simulation simulation(problem);
      const std::string setup = peridot::describe_setup(simulation);
      if (root) std::cout << deck << ": valid\n" << setup;
      return 0;
    }
    peridot::RunOptions options;
    options.progress = !quiet;
    options.log = quiet || !root ? nullptr : &std::cout;
    options.restart = restart;
    // Stopped by a signal after a step: the shell's convention, 128 + the signal's number.
    const peridot::RunOutcome outcome = peridot::run_problem(problem, options);
    return outcome.signal == 0 ? 0 : 128 + outcome.signal;
  } catch (const peridot::InputError& e) {
    return report(e);
  } catch (const peridot::NumericalError& e) {
    // Distributed, every rank holds the failing rank's message (Simulation::step).
    if (root) std::cerr << "\nerror: " << e.what() << "\noutputs written so far are closed and readable\n";
    return exit_numerical_error;
  } catch (const peridot::OutputError& e) {
    if (root) std::cerr << "error: " << e.what() << '\n';  // every rank stops with rank 0's message
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    // A failure that only this rank saw: the others cannot be reached any more; end them all.
    if (!peridot::Communicator::world().serial()) peridot::MpiSession::abort(1);
    return 1;
  }
}
