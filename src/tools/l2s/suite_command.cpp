// l2s suite OUT_DIR: the paper's experiments (Figs. 5-7) in one command.
// Groups of cells run on --jobs worker threads; each finished group's rows are
// appended to OUT_DIR/results.csv at once, so an interrupted run resumes where
// it stopped. At the end: sorted results.csv, summary.md, plots (matplotlib).

#include "commands.hpp"
#include "progress_bar.hpp"

#include <l2s/error.hpp>
#include <l2s/sim/suite.hpp>
#include <l2s/sim/suite_results.hpp>

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace l2s::cli {
namespace {

struct SuiteCommandOptions {
  std::string out_dir;
  std::string experiment = "all";
  std::vector<std::string> presets = {"both"};
  std::string thresholds;
  int repeats = 3;
  int scene_count = 20;
  int scene_frames = 20;
  std::string scene_boards = "all";
  int jobs = 0;
  std::uint64_t seed = 1;
  bool quick = false;
  bool no_plots = false;
};

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) {
  g_interrupted = true;
  static const char message[] =
      "\nl2s suite: interrupted; finishing the running groups (Ctrl-C again to stop now)\n";
  [[maybe_unused]] const auto ignored = ::write(STDERR_FILENO, message, sizeof message - 1);
  std::signal(SIGINT, SIG_DFL);
}

// Scenes in --quick: a few, enough to see that other rigs and lidars still work.
constexpr int kQuickScenes = 3;

// Options given on the command line (their defaults differ under --quick).
struct GivenOptions {
  bool repeats = false;
  bool count = false;
  bool scene_boards = false;
};

sim::SuiteOptions suite_options(const SuiteCommandOptions& o, const GivenOptions& given) {
  sim::SuiteOptions options;
  if (o.quick)
    options.experiments = {"quick", "scenes"};
  else if (o.experiment != "all")
    options.experiments = {o.experiment};
  options.scene_count = o.quick && !given.count ? kQuickScenes : o.scene_count;
  options.scene_frames = o.scene_frames;
  // --quick keeps the scenes its thresholds were measured on: the classic faces.
  options.scene_boards = o.scene_boards == "marked" ? sim::BoardDraw::Marked
                         : (o.quick && !given.scene_boards) || o.scene_boards == "classic" ? sim::BoardDraw::Classic
                                                                                            : sim::BoardDraw::All;
  options.presets.clear();
  for (const std::string& preset : o.presets)
    for (const char* name : preset == "both" ? std::vector<const char*>{"default", "paper"}
                                             : std::vector<const char*>{preset.c_str()})
      if (std::find(options.presets.begin(), options.presets.end(), name) == options.presets.end())
        options.presets.push_back(name);
  options.repeats = o.quick && !given.repeats ? 1 : o.repeats;
  options.seed = o.seed;
  return options;
}

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The plot script: beside an installed tool, or in the source tree it was built from.
std::string find_plot_script() {
  if (const char* env = std::getenv("L2S_PLOT_SCRIPT")) return env;
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "l2scalib" / "plot_suite.py";
    if (fs::exists(installed)) return installed.string();
  }
  return L2S_PLOT_SCRIPT_SOURCE;
}

void make_plots(const std::string& out_dir) {
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string script = find_plot_script();
  const std::string command = python + " " + shell_quote(script) + " " + shell_quote(out_dir);
  const bool have_matplotlib =
      std::system((python + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) == 0;
  if (!fs::exists(script) || !have_matplotlib) {
    std::printf("plots     skipped (%s); to draw them: %s\n",
                fs::exists(script) ? "python3 with matplotlib not found" : "plot_suite.py not found",
                command.c_str());
    return;
  }
  std::fflush(stdout);  // our lines before the script's
  if (std::system(command.c_str()) != 0)
    std::fprintf(stderr, "l2s: warning: the plot script failed: %s\n", command.c_str());
}

void write_text(const fs::path& path, const std::string& text) {
  const fs::path temporary = path.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    if (!out.flush()) throw FileError(temporary.string(), "cannot write");
  }
  fs::rename(temporary, path);
}

// A group with the cells a resumed run still has to do.
struct Pending {
  const sim::SuiteGroup* group;
  std::vector<sim::SuiteCell> cells;
};

// The groups with cells not yet in results.csv, and the frames they will simulate.
std::vector<Pending> pending_groups(const std::vector<sim::SuiteGroup>& plan, const sim::SuiteResume& resume,
                                   std::size_t& total_frames, std::size_t& cells_total) {
  std::vector<Pending> pending;
  total_frames = 0;
  cells_total = 0;
  for (const auto& group : plan) {
    Pending p{&group, {}};
    for (const auto& cell : group.cells)
      if (!resume.done.count(cell.key())) p.cells.push_back(cell);
    cells_total += group.cells.size();
    if (p.cells.empty()) continue;
    total_frames += group.frames;
    pending.push_back(std::move(p));
  }
  return pending;
}

// Runs the pending groups on `jobs` worker threads, appending each finished
// group's rows to `csv` at once (so an interrupted run resumes after it).
// Rethrows a worker's exception; returns the groups finished (fewer than
// pending.size() when interrupted).
std::size_t run_groups(const std::vector<Pending>& pending, int jobs, int sim_threads, std::size_t total_frames,
                       std::ofstream& csv) {
  std::mutex mutex;
  std::exception_ptr failure;
  std::atomic<std::size_t> next{0};
  std::size_t frames_done = 0, groups_done = 0;
  ProgressBar progress("suite", total_frames);
  g_interrupted = false;
  std::signal(SIGINT, on_interrupt);

  const auto worker = [&] {
    for (;;) {
      const std::size_t index = next.fetch_add(1);
      if (index >= pending.size() || g_interrupted) return;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (failure) return;
      }
      try {
        const auto rows = sim::run_suite_group(*pending[index].group, pending[index].cells, sim_threads, [&] {
          std::lock_guard<std::mutex> lock(mutex);
          progress.update(++frames_done);
        });
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& row : rows) csv << sim::to_csv_line(row) << '\n';
        csv.flush();
        ++groups_done;
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> workers;
  for (int j = 1; j < jobs; ++j) workers.emplace_back(worker);
  worker();
  for (auto& thread : workers) thread.join();
  std::signal(SIGINT, SIG_DFL);
  csv.close();
  if (failure) std::rethrow_exception(failure);
  if (!g_interrupted && total_frames > 0) progress.finish();
  return groups_done;
}

// The final files: results.csv in reading order (whatever the number of
// jobs), summary.md and the plots. Returns the sorted rows.
std::vector<sim::SuiteRow> write_results(const SuiteCommandOptions& o, const std::string& csv_path) {
  std::vector<sim::SuiteRow> rows = sim::read_suite_csv(csv_path).rows;
  sim::sort_suite_rows(rows);
  sim::write_suite_csv(csv_path, rows);
  const std::string summary = sim::suite_summary_markdown(rows);
  write_text(fs::path(o.out_dir) / "summary.md", summary);
  std::printf("wrote     %s\n          %s\n", csv_path.c_str(), (fs::path(o.out_dir) / "summary.md").c_str());
  if (o.quick) std::printf("\n%s\n", summary.c_str());
  if (!o.no_plots) make_plots(o.out_dir);
  return rows;
}

// --thresholds: the rows of the planned cells against the limits; the exit code.
int check_thresholds(const std::vector<sim::SuiteGroup>& plan, const std::vector<sim::SuiteRow>& rows,
                     const sim::SuiteThresholds& thresholds, const std::string& thresholds_path) {
  std::set<std::string> planned;
  for (const auto& group : plan)
    for (const auto& cell : group.cells) planned.insert(cell.key());
  std::vector<sim::SuiteRow> checked;
  for (const auto& row : rows)
    if (planned.count(row.cell_key())) checked.push_back(row);
  const auto violations = sim::check_suite_thresholds(checked, thresholds);
  for (const auto& violation : violations) std::fprintf(stderr, "l2s suite: threshold: %s\n", violation.c_str());
  if (!violations.empty()) {
    std::fprintf(stderr, "l2s suite: %zu threshold violation(s) (limits in %s)\n", violations.size(),
                 thresholds_path.c_str());
    return 1;
  }
  std::printf("thresholds passed (%s)\n", thresholds_path.c_str());
  return 0;
}

int run_suite(const SuiteCommandOptions& o, const GivenOptions& given) {
  const sim::SuiteOptions options = suite_options(o, given);
  const std::vector<sim::SuiteGroup> plan = sim::make_suite_plan(options);
  fs::create_directories(o.out_dir);
  const std::string csv_path = (fs::path(o.out_dir) / "results.csv").string();
  const sim::SuiteThresholds thresholds =
      o.thresholds.empty() ? sim::SuiteThresholds{} : sim::read_suite_thresholds(o.thresholds);

  // Resume: keep the rows of finished cells, run the rest.
  const sim::SuiteCsv earlier = sim::read_suite_csv(csv_path);
  const sim::SuiteResume resume = sim::resume_suite(plan, earlier.rows);
  if (!fs::exists(csv_path) || earlier.trimmed || resume.dropped > 0)
    sim::write_suite_csv(csv_path, resume.kept);
  std::size_t total_frames = 0, cells_total = 0;
  const std::vector<Pending> pending = pending_groups(plan, resume, total_frames, cells_total);
  if (!resume.done.empty())
    std::printf("resume    %zu of %zu cells already in %s%s\n", resume.done.size(), cells_total,
                csv_path.c_str(), earlier.trimmed ? " (an interrupted last line was dropped)" : "");

  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = std::max(1, std::min<int>(o.jobs > 0 ? o.jobs : static_cast<int>(hardware),
                                             static_cast<int>(std::max<std::size_t>(pending.size(), 1))));
  // Cores not used by group workers go to the simulator's own threads.
  const int sim_threads = std::max(1, static_cast<int>(hardware) / jobs);
  std::ofstream csv(csv_path, std::ios::app | std::ios::binary);
  if (!csv) throw FileError(csv_path, "cannot open for appending");
  const std::size_t groups_done = run_groups(pending, jobs, sim_threads, total_frames, csv);
  if (g_interrupted) {
    std::fprintf(stderr, "\nl2s suite: stopped after %zu of %zu groups; run the same command again to resume\n",
                 groups_done, pending.size());
    return 1;
  }

  const std::vector<sim::SuiteRow> rows = write_results(o, csv_path);
  if (o.thresholds.empty()) return 0;
  return check_thresholds(plan, rows, thresholds, o.thresholds);
}

}  // namespace

void add_suite_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand(
      "suite", "Run the paper's experiments on simulated data: results.csv, summary.md, plots");
  auto options = std::make_shared<SuiteCommandOptions>();
  command->add_option("out_dir", options->out_dir, "output folder (resumed when it holds results.csv)")
      ->required();
  command->add_option("--experiment", options->experiment,
                      "frames (Fig. 5), noise (Fig. 6), lidars (Fig. 7), all (the three), or scenes "
                      "(randomised rigs, scenes and lidars), or poses (1, 2, 3, 5 board poses), mono (the same "
                      "with the left camera alone and the board's markers), lidar-pair (VLP-16 to HDL-32E)")
      ->check(CLI::IsMember({"frames", "noise", "lidars", "all", "scenes", "poses", "mono", "lidar-pair"}));
  command->add_option("--count", options->scene_count, "scenes of --experiment scenes (--quick: 3)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--scene-frames", options->scene_frames, "frames per random scene")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  command->add_option("--scene-boards", options->scene_boards,
                      "boards and mountings of random scenes: all (printed, painted, decorated and glossy faces, "
                      "markers, other sizes and hole layouts; rolled rigs, upside-down lidars, depth-camera, 5 MP "
                      "and long-baseline pairs) or classic (the default board, matte, wood or low-contrast, no "
                      "markers, a level rig, an upright lidar; --quick's default) or marked (the boards and rigs of "
                      "all, always with markers, a level rig, an upright lidar)")
      ->check(CLI::IsMember({"all", "classic", "marked"}))
      ->capture_default_str();
  command->add_option("--repeats", options->repeats, "repetitions per cell, independent seeds")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  command->add_option("--jobs", options->jobs, "worker threads over groups of cells (0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--preset", options->presets,
                      "calibrator preset(s), comma-separated: default, paper, both (the two), or mono (scenes: the "
                      "default preset on the left camera alone, by the board's markers, beside the stereo runs)")
      ->delimiter(',')
      ->check(CLI::IsMember({"default", "paper", "both", "mono"}))
      ->capture_default_str();
  command->add_flag("--quick", options->quick,
                    "CI smoke test: settings 1, 3, 8 x VLP-16 x K=1 x 10 frames, 1 repetition, and 3 random scenes");
  command->add_option("--seed", options->seed, "base seed; every cell's seed derives from it")
      ->capture_default_str();
  command->add_option("--thresholds", options->thresholds,
                      "YAML limits per preset; exit 1 when a cell breaks them")
      ->check(CLI::ExistingFile);
  command->add_flag("--no-plots", options->no_plots, "do not run scripts/plot_suite.py");
  command->callback([&runner, options, command] {
    GivenOptions given;
    given.repeats = command->count("--repeats") > 0;
    given.count = command->count("--count") > 0;
    given.scene_boards = command->count("--scene-boards") > 0;
    runner = [options, given] { return run_suite(*options, given); };
  });
}

}  // namespace l2s::cli
