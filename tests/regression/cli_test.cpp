// The command-line program end to end: exit statuses, error positions, nothing written for a bad deck,
// a numerical blow-up reported with step, time and point, and bitwise-identical results for 1 and 2
// threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <system_error>

#include <chrono>
#include <csignal>
#include <thread>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "peridot/materials/models.hpp"

namespace {

namespace fs = std::filesystem;

struct Result {
  int status = -1;
  std::string output;  ///< stdout and stderr together
};

Result run(const std::string& arguments) {
  const std::string command = std::string(PERIDOT_EXECUTABLE) + " " + arguments + " 2>&1";
  Result result;
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer;
  while (std::fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// This process's scratch folder, removed when the process ends with every test passed (a failure leaves it to be
// looked at): ctest runs each test in a process of its own.
const fs::path& scratch_root() {
  static const struct Root {
    fs::path path = fs::temp_directory_path() / ("peridot_cli_" + std::to_string(::getpid()));
    ~Root() {
      if (::testing::UnitTest::GetInstance()->Passed()) {
        std::error_code ignored;
        fs::remove_all(path, ignored);
      }
    }
  } root;
  return root.path;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = scratch_root() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const fs::path source = PERIDOT_SOURCE_DIR;

// Every tests/data/decks/bad_*.yaml opens with "# expect: LINE:COL message": the run must exit 2, print
// "<file>:LINE:COL: error: ...message...", and create no output directory.
TEST(Cli, BadDecksExitTwoWithPositionAndWriteNothing) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(source / "tests" / "data" / "decks")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("bad_", 0) != 0) continue;
    const fs::path dir = scratch(entry.path().stem().string());
    const fs::path deck = dir / name;
    fs::copy_file(entry.path(), deck);
    std::string first_line;
    std::getline(std::ifstream(deck), first_line);
    std::smatch match;
    ASSERT_TRUE(std::regex_match(first_line, match, std::regex(R"(# expect: (\d+):(\d+) (.*))"))) << name;
    const Result result = run("run " + deck.string());
    EXPECT_EQ(result.status, 2) << name << "\n" << result.output;
    const std::string where = deck.string() + ":" + match[1].str() + ":" + match[2].str() + ": error: ";
    EXPECT_NE(result.output.find(where), std::string::npos) << name << ": expected '" << where << "' in\n" << result.output;
    EXPECT_NE(result.output.find(match[3].str()), std::string::npos) << name << ": expected '" << match[3] << "' in\n"
                                                                      << result.output;
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
    EXPECT_EQ(entries, 1u) << name << ": something was written beside the deck";
    ++checked;
  }
  EXPECT_GE(checked, 9);
}

TEST(Cli, ReportsEveryErrorAtOnce) {
  const fs::path dir = scratch("many");
  const fs::path deck = dir / "deck.yaml";
  std::string text = read_file(source / "tests" / "data" / "decks" / "bad_unknown_key.yaml");
  text = std::regex_replace(text, std::regex("density: 7800"), "density: -1");
  text = std::regex_replace(text, std::regex("model: lps"), "model: lsp");
  std::ofstream(deck) << text;
  const Result result = run("check " + deck.string());
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find("critical_strech"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("density"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("lsp"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("3 errors"), std::string::npos) << result.output;
}

TEST(Cli, CheckDescribesTheRun) {
  const Result result = run("check " + (source / "tests" / "regression" / "decks" / "exodus_small.yaml").string());
  EXPECT_EQ(result.status, 0) << result.output;
  for (const char* expected : {"points", "bonds", "memory", "stable time step", "steps"})
    EXPECT_NE(result.output.find(expected), std::string::npos) << expected << " missing in\n" << result.output;
}

// Bad command-line values end like bad decks: exit 2, a message naming the option, nothing written.
TEST(Cli, BadCommandLineValuesExitTwoAndWriteNothing) {
  const std::string deck = (source / "tests" / "regression" / "decks" / "exodus_small.yaml").string();
  const fs::path dir = scratch("command_line");
  const std::string output = " -o " + (dir / "out").string() + " ";
  const std::pair<const char*, const char*> cases[] = {{"-t 0", "--threads"},           {"-t -3", "--threads"},
                                                       {"-t 100000", "--threads"},      {"-t two", "--threads"},
                                                       {"--max-memory lots", "--max-memory"}, {"--no-such-option", "--no-such-option"}};
  for (const auto& [option, named] : cases) {
    const Result result = run("run -q " + std::string(option) + output + deck);
    EXPECT_EQ(result.status, 2) << option << "\n" << result.output;
    EXPECT_NE(result.output.find(named), std::string::npos) << option << "\n" << result.output;
  }
  // A memory limit below what the deck's points and bonds need: refused with the estimate, at the body.
  const Result small = run("run -q --max-memory 10KiB" + output + deck);
  EXPECT_EQ(small.status, 2) << small.output;
  EXPECT_NE(small.output.find("allowed by --max-memory"), std::string::npos) << small.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  EXPECT_EQ(run("check --max-memory 1GiB " + deck).status, 0);
  EXPECT_EQ(run("run --help").status, 0);
}

TEST(Cli, InfoListsModelsAndKeys) {
  const Result result = run("info");
  EXPECT_EQ(result.status, 0);
  for (const char* expected : {"pmb", "lps", "critical_stretch", "fracture_energy", "horizon_factor", "safety_factor"})
    EXPECT_NE(result.output.find(expected), std::string::npos) << expected;
}

// docs/deck.md is generated by `peridot info --markdown`; it must not drift from the schema.
TEST(Cli, DeckReferenceIsUpToDate) {
  const Result result = run("info --markdown");
  ASSERT_EQ(result.status, 0);
  EXPECT_EQ(result.output, read_file(source / "docs" / "deck.md"))
      << "regenerate with: peridot info --markdown > docs/deck.md";
}

// A finished run's results replace the previous ones; an output name that is a symlink is replaced, not
// followed out of the folder.
TEST(Cli, ResultsReplaceSymlinksInsteadOfFollowingThem) {
  const fs::path dir = scratch("symlink");
  const std::string deck = (source / "tests" / "regression" / "decks" / "exodus_small.yaml").string();
  fs::create_directories(dir / "out");
  std::ofstream(dir / "victim.csv") << "keep";
  fs::create_symlink(dir / "victim.csv", dir / "out" / "history.csv");
  ASSERT_EQ(run("run -q -o " + (dir / "out").string() + " " + deck).status, 0);
  EXPECT_EQ(read_file(dir / "victim.csv"), "keep");
  EXPECT_FALSE(fs::is_symlink(dir / "out" / "history.csv"));
  EXPECT_NE(read_file(dir / "out" / "history.csv").find("time,step"), std::string::npos);
  for (const char* partial : {"small.e.partial", "history.csv.partial", "resolved_deck.yaml.partial"})
    EXPECT_FALSE(fs::exists(dir / "out" / partial)) << partial;
}

// SIGTERM (as a batch system sends) stops a run after the step in progress, with that step's frame and history
// row written: exit 128 + 15, the results in *.partial files, and the earlier finished run's results untouched.
TEST(Cli, SignalStopsAfterAStepAndKeepsTheFinishedResults) {
  const fs::path dir = scratch("signal");
  const fs::path out = dir / "out";
  const fs::path small = source / "tests" / "regression" / "decks" / "exodus_small.yaml";
  ASSERT_EQ(run("run -q -o " + out.string() + " " + small.string()).status, 0);
  const std::string finished = read_file(out / "small.e"), finished_history = read_file(out / "history.csv");
  ASSERT_FALSE(finished.empty());

  const fs::path deck = dir / "long.yaml";
  std::ofstream(deck) << std::regex_replace(read_file(small), std::regex("num_steps: 120"), "num_steps: 100000000");
  const fs::path messages = dir / "stderr.txt";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int fd = ::open(messages.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 2);
    ::execl(PERIDOT_EXECUTABLE, "peridot", "run", "-q", "-t", "1", "-o", out.c_str(), deck.c_str(), nullptr);
    ::_exit(127);
  }
  // Stop it once it has written some rows.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline &&
         (!fs::exists(out / "history.csv.partial") || fs::file_size(out / "history.csv.partial") < 20000))
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "killed instead of stopping";
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  const std::string said = read_file(messages);
  std::smatch step;
  ASSERT_TRUE(std::regex_search(said, step, std::regex(R"(stopped by SIGTERM after step (\d+) of 100000000)"))) << said;
  // The last history row is the step it stopped after; the finished run's results are byte for byte as they were.
  const std::string history = read_file(out / "history.csv.partial");
  const std::string last_row = history.substr(history.rfind('\n', history.size() - 2) + 1);
  EXPECT_EQ(last_row.substr(last_row.find(',') + 1, step[1].length() + 1), step[1].str() + ",") << last_row;
  EXPECT_TRUE(fs::file_size(out / "small.e.partial") > 0);
  EXPECT_TRUE(read_file(out / "small.e") == finished);
  EXPECT_EQ(read_file(out / "history.csv"), finished_history);
  EXPECT_NE(read_file(out / "run.log").find("stopped by SIGTERM"), std::string::npos);
}

// A time step far above the stable one blows up: exit 3, a message naming step, time, point, position and the
// likely cause, and the frames written before the failure still readable (the history has its rows).
TEST(Cli, BlowUpExitsThreeNamingStepTimeAndPoint) {
  const fs::path dir = scratch("blowup");
  const fs::path deck = dir / "deck.yaml";
  std::string text = read_file(source / "tests" / "regression" / "decks" / "exodus_small.yaml");
  text = std::regex_replace(text, std::regex("  num_steps: 120"), "  num_steps: 400\n  time_step: 2e-6");
  text = std::regex_replace(text, std::regex("    damage: \\{critical_stretch: 0.002\\}\n"), "");  // no bond can break
  std::ofstream(deck) << text;
  const Result result = run("run -q " + deck.string());
  EXPECT_EQ(result.status, 3) << result.output;
  EXPECT_TRUE(std::regex_search(result.output, std::regex(R"(at step \d+, time [0-9.e+-]+ s, point \d+ .* at \()")))
      << result.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "small.e"));
  // Caught while still finite: 100 times the problem's size, long before inf.
  EXPECT_NE(read_file(dir / "out" / "run.log").find("error: runaway displacement"), std::string::npos);
  EXPECT_NE(result.output.find("more than 100 times the problem's size"), std::string::npos) << result.output;
}

// A time step just above the stable one (1.1 times) grows slowly: the kinetic energy passes ten times the energy
// ever supplied long before any displacement is large. Exit 3 naming the step and the fastest point.
TEST(Cli, KineticEnergyGrowingWithoutSourceExitsThree) {
  const fs::path dir = scratch("energy_growth");
  const fs::path deck = dir / "deck.yaml";
  std::string text = read_file(source / "tests" / "regression" / "decks" / "exodus_small.yaml");
  text = std::regex_replace(text, std::regex("  num_steps: 120"), "  num_steps: 20000\n  time_step: 2.143471e-7");
  text = std::regex_replace(text, std::regex("    damage: \\{critical_stretch: 0.002\\}\n"), "");
  std::ofstream(deck) << text;
  const Result result = run("run -q " + deck.string());
  EXPECT_EQ(result.status, 3) << result.output;
  std::smatch step;
  ASSERT_TRUE(std::regex_search(result.output, step,
                                std::regex(R"(kinetic energy growing without a source at step (\d+), time [0-9.e+-]+ s: .* fastest point \d+ .* at \()")))
      << result.output;
  // The displacement criterion alone stops this run only at step 17051.
  EXPECT_LT(std::stoi(step[1]), 10000);
  EXPECT_NE(result.output.find("stable Δt"), std::string::npos);
}

// A history total that overflows while every point's values are finite (a density of 1e300 at 1e9 m/s: the
// kinetic energy is inf) stops the run like a non-finite point value: exit 3, the column named, the row kept.
TEST(Cli, NonFiniteHistoryTotalExitsThree) {
  const fs::path dir = scratch("overflow");
  const fs::path deck = dir / "deck.yaml";
  std::string text = read_file(source / "tests" / "regression" / "decks" / "exodus_small.yaml");
  text = std::regex_replace(text, std::regex("density: [0-9.e+]+"), "density: 1e300");
  text = std::regex_replace(text, std::regex(R"(velocity: \{y: "20 \* \(y - 0.01\) / 0.01"\})"), R"(velocity: {y: "1e9"})");
  std::ofstream(deck) << text;
  const Result result = run("run -q " + deck.string());
  EXPECT_EQ(result.status, 3) << result.output;
  EXPECT_NE(result.output.find("non-finite kinetic_energy in the history at step 0"), std::string::npos) << result.output;
  const std::string history = read_file(dir / "out" / "history.csv");
  EXPECT_NE(history.find(",inf,"), std::string::npos) << history;
}

/// Runs `deck` with 1 and 2 threads into scratch folders named after `name`; expects every byte of small.e
/// and history.csv identical, and returns the 1-thread folder.
fs::path expect_identical_with_one_and_two_threads(const std::string& deck_name, const std::string& name) {
  const fs::path deck = source / "tests" / "regression" / "decks" / deck_name;
  const fs::path one = scratch(name + "1"), two = scratch(name + "2");
  EXPECT_EQ(run("run -q -t 1 -o " + one.string() + " " + deck.string()).status, 0);
  EXPECT_EQ(run("run -q -t 2 -o " + two.string() + " " + deck.string()).status, 0);
  for (const char* file : {"small.e", "history.csv"}) {
    const std::string a = read_file(one / file), b = read_file(two / file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_TRUE(a == b) << file << " differs between 1 and 2 threads";
  }
  return one;
}

// Same deck, 1 and 2 threads: every output byte identical (Exodus frames and history).
TEST(Cli, OneAndTwoThreadsGiveIdenticalBits) { expect_identical_with_one_and_two_threads("exodus_small.yaml", "threads"); }

// Two inelastic blocks (lps_plastic beside lps_viscoelastic): plastic flow, viscous relaxation and bonds
// breaking across their interface, with 1 and 2 threads.
TEST(Cli, InelasticOneAndTwoThreadsGiveIdenticalBits) {
  expect_identical_with_one_and_two_threads("inelastic_small.yaml", "inelastic_threads");
}

// Bonds breaking by their work (damage criterion: energy): 1 and 2 threads give identical bits; the crack
// grew, and the run log gives the block's N_c (36 for δ = 3.015Δx in 2D).
TEST(Cli, EnergyFailureOneAndTwoThreadsGiveIdenticalBits) {
  const fs::path one = expect_identical_with_one_and_two_threads("energy_failure_small.yaml", "energy_threads");
  std::istringstream rows(read_file(one / "history.csv"));
  std::string header, row, last;
  std::getline(rows, header);
  while (std::getline(rows, row)) last = row;
  auto cells = [](const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
    return out;
  };
  const std::vector<std::string> names = cells(header), values = cells(last);
  const auto column = std::find(names.begin(), names.end(), "max_damage") - names.begin();
  ASSERT_LT(static_cast<std::size_t>(column), values.size()) << header << "\n" << last;
  EXPECT_GT(std::stod(values[static_cast<std::size_t>(column)]), 0.3) << "the crack grew: " << last;
  const Result check = run("check " + (source / "tests" / "regression" / "decks" / "energy_failure_small.yaml").string());
  EXPECT_NE(check.output.find("N_c 36 micropotentials per cell"), std::string::npos) << check.output;
}

// Dynamic relaxation in load steps with bonds breaking between equilibria: 1 and 2 threads give identical
// bits (the damping coefficient's and the residual's sums are exact integer sums); bonds did break.
TEST(Cli, RelaxationOneAndTwoThreadsGiveIdenticalBits) {
  const fs::path one = expect_identical_with_one_and_two_threads("relaxation_notch.yaml", "relaxation_threads");
  const std::string history = read_file(one / "history.csv");
  EXPECT_NE(history.find("load_factor,residual,iterations,bonds_broken"), std::string::npos) << history;
  std::istringstream rows(history);
  std::string row, last;
  while (std::getline(rows, row)) last = row;
  EXPECT_EQ(last.rfind("1,3,", 0), 0u) << "the last row is load step 3 at t = 1 s: " << last;
  std::istringstream cells(last);
  std::vector<double> values;
  for (std::string cell; std::getline(cells, cell, ',');) values.push_back(std::stod(cell));
  EXPECT_GT(values[8], 0.1) << "max_damage: the notch grew";
}

// The correspondence model: 1 and 2 threads give identical bits (the gathers and sums do not depend on the
// split), the history has the hourglass work and the Exodus file the correspondence fields.
TEST(Cli, CorrespondenceOneAndTwoThreadsGiveIdenticalBits) {
  const fs::path one = expect_identical_with_one_and_two_threads("correspondence_small.yaml", "corr_threads");
  EXPECT_NE(read_file(one / "history.csv").find("hourglass_work"), std::string::npos);
  const std::string exodus = read_file(one / "small.e");  // netCDF keeps variable names as plain text
  for (const char* field : {"deformation_gradient_zy", "cauchy_stress_zx", "von_mises_stress", "green_lagrange_strain_xy",
                            "equivalent_plastic_strain", "dissipation"})
    EXPECT_NE(exodus.find(field), std::string::npos) << field;
}

// Johnson–Cook damage through the influence function (a notched bar pulled apart): bonds degrade and break,
// points fail and fly free, and 1 and 2 threads still give identical bits; the bar did break.
TEST(Cli, JohnsonCookDamageOneAndTwoThreadsGiveIdenticalBits) {
  const fs::path one = expect_identical_with_one_and_two_threads("jc_damage_small.yaml", "jc_damage_threads");
  const std::string exodus = read_file(one / "small.e");
  EXPECT_NE(exodus.find("material_damage"), std::string::npos);
  EXPECT_NE(exodus.find("fragment"), std::string::npos);
  std::istringstream rows(read_file(one / "history.csv"));
  std::string header, row, last;
  std::getline(rows, header);
  while (std::getline(rows, row)) last = row;
  EXPECT_NE(header.find("broken_fraction"), std::string::npos) << header;
  std::istringstream cells(last);
  std::vector<double> values;
  for (std::string cell; std::getline(cells, cell, ',');) values.push_back(std::stod(cell));
  EXPECT_GT(values[8], 0.99) << "max_damage: some point lost every bond: " << last;
}

// A correspondence point whose deformation gradient inverts (a cube hit at 20 km/s): exit 3 naming step,
// time and point, the history written so far kept.
TEST(Cli, CorrespondenceInvertedDeformationExitsThree) {
  const fs::path dir = scratch("corr_inverted");
  const fs::path deck = dir / "deck.yaml";
  std::string text = read_file(source / "tests" / "regression" / "decks" / "correspondence_small.yaml");
  text = std::regex_replace(text, std::regex(R"(\{velocity: \{.*\}\})"), R"v({velocity: {x: "-2e4*sin(3000*x)"}})v");
  std::ofstream(deck) << text;
  const Result result = run("run -q " + deck.string());
  EXPECT_EQ(result.status, 3) << result.output;
  EXPECT_TRUE(std::regex_search(result.output, std::regex(R"(at step \d+, time [0-9.e+-]+ s: correspondence model: point \d+ \(input id \d+\) at \()")))
      << result.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "history.csv"));
}

// The log closes with the largest εp and the highest temperature of a plastic correspondence run, and warns (on
// stderr too, for a quiet run) when points heat to T* ≥ 0.99 (99 % of the way to the melting temperature): here
// the Johnson–Cook bar of the damage tests with its melting point lowered to 2 K above the initial temperature and
// a softening exponent of 5 (Θ = 1 − T*⁵ falls fast near T_m, so T* passes 0.99 within the few per cent of strain the bar reaches).
TEST(Cli, PlasticRunNamesItsHottestPointAndWarnsOfMelting) {
  const std::string deck_text = read_file(source / "tests" / "regression" / "decks" / "jc_damage_small.yaml");
  const std::regex end_time("  end_time: 30 us"), melting("melting_temperature: 925 K, exponent: 1.34");
  const fs::path cold = scratch("plastic_summary"), hot = scratch("plastic_melting");
  std::ofstream(cold / "deck.yaml") << std::regex_replace(deck_text, end_time, "  end_time: 10 us");
  std::ofstream(hot / "deck.yaml") << std::regex_replace(std::regex_replace(deck_text, end_time, "  end_time: 10 us"),
                                                         melting, "melting_temperature: 296 K, exponent: 5");
  const Result quiet = run("run -q " + (cold / "deck.yaml").string());
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_EQ(quiet.output, "");
  const std::string log = read_file(cold / "out" / "run.log");
  const std::regex summary(R"(plasticity: largest equivalent plastic strain [0-9.e+-]+ at input id \d+, reference position \(.*\) m\n)"
                           R"(plasticity: highest temperature [0-9.e+-]+ K at input id \d+)");
  EXPECT_TRUE(std::regex_search(log, summary)) << log;
  EXPECT_EQ(log.find("melting"), std::string::npos) << log;

  const Result melted = run("run -q " + (hot / "deck.yaml").string());
  ASSERT_EQ(melted.status, 0) << melted.output;
  EXPECT_TRUE(std::regex_search(melted.output, std::regex(R"(^warning: \d+ points? heated to T\* ≥ 0\.99 \(99 % of the way from the reference to the melting)")))
      << melted.output;
  EXPECT_NE(read_file(hot / "out" / "run.log").find("heated to T* ≥ 0.99"), std::string::npos);
}

// docs/models/<name>.md are generated by `peridot info --model <name> --markdown`; they must not drift from
// the registry and the schema.
TEST(Cli, ModelPagesAreUpToDate) {
  for (std::string_view model : peridot::model_names()) {
    const Result result = run(fmt::format("info --model {} --markdown", model));
    ASSERT_EQ(result.status, 0) << result.output;
    EXPECT_EQ(result.output, read_file(source / "docs" / "models" / fmt::format("{}.md", model)))
        << "regenerate with: peridot info --model " << model << " --markdown > docs/models/" << model << ".md";
  }
  EXPECT_NE(run("info --model nonesuch").status, 0);
}

}  // namespace
