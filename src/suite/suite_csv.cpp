// results.csv of `l2s suite`: RFC 4180 lines, one per evaluation, appended as
// cells finish; read back (dropping an interrupted last line) to resume.

#include <l2s/sim/suite_results.hpp>

#include <l2s/error.hpp>

#include "detail/atomic_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

namespace l2s::sim {
namespace {

constexpr const char* kHeader =
    "experiment,setting,lidar,noise_k,frames,preset,seed,repetition,success,reason,e_t_m,e_r_rad,"
    "lidar_frames,camera_frames,wall_s,scene,verdict,covered,check_reasons,e_lidar_centres_m,e_camera_centres_m,"
    "bound_t_m,bound_r_rad,face,markers,roll_deg,lens";
constexpr std::size_t kColumns = 27;
// results.csv of earlier releases: without what a scene drew, before that
// without the stated bounds, before that
// without the centres' errors, before that without check_reasons, and before
// that without covered
constexpr std::size_t kColumnsBeforeDraws = 23;
constexpr std::size_t kColumnsBeforeBounds = 21;
constexpr std::size_t kColumnsBeforeCentres = 19;
constexpr std::size_t kColumnsBeforeReasons = 18;
constexpr std::size_t kColumnsBeforeCovered = 17;

std::string quote(const std::string& text) {
  std::string flat = text;
  std::replace(flat.begin(), flat.end(), '\n', ' ');
  std::replace(flat.begin(), flat.end(), '\r', ' ');
  if (flat.find_first_of(",\"") == std::string::npos) return flat;
  std::string out = "\"";
  for (const char c : flat) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  if (quoted) throw Error("unterminated quote");
  return fields;
}

// Full precision for errors (they are compared and plotted), short otherwise.
std::string number(double value, int digits) {
  if (std::isnan(value)) return "nan";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

double to_double(const std::string& text) {
  if (text == "nan" || text.empty()) return std::nan("");
  std::size_t used = 0;
  const double value = std::stod(text, &used);
  if (used != text.size()) throw Error("not a number: '" + text + "'");
  return value;
}

int to_int(const std::string& text) {
  std::size_t used = 0;
  const int value = std::stoi(text, &used);
  if (used != text.size()) throw Error("not an integer: '" + text + "'");
  return value;
}

}  // namespace

std::string suite_csv_header() { return kHeader; }

std::string to_csv_line(const SuiteRow& r) {
  std::ostringstream out;
  out << quote(r.experiment) << ',' << r.setting << ',' << quote(r.lidar) << ',' << number(r.noise_k, 6)
      << ',' << r.frames << ',' << quote(r.preset) << ',' << r.seed << ',' << r.repetition << ','
      << (r.success ? 1 : 0) << ',' << quote(r.reason) << ',' << number(r.e_t, 17) << ','
      << number(r.e_r, 17) << ',' << r.lidar_frames << ',' << r.camera_frames << ','
      << number(r.wall_s, 4) << ',' << quote(r.scene) << ',' << quote(r.verdict) << ',' << r.covered << ','
      << quote(r.check_reasons) << ',' << number(r.e_lidar_centres, 17) << ',' << number(r.e_camera_centres, 17)
      << ',' << number(r.bound_t, 17) << ',' << number(r.bound_r, 17) << ',' << quote(r.face) << ','
      << quote(r.markers) << ',' << number(r.roll * 180.0 / M_PI, 6) << ',' << quote(r.lens);
  return out.str();
}

SuiteRow parse_csv_line(const std::string& line) {
  const auto f = split_csv(line);
  if (f.size() != kColumns && f.size() != kColumnsBeforeDraws && f.size() != kColumnsBeforeBounds && f.size() != kColumnsBeforeCentres &&
      f.size() != kColumnsBeforeReasons && f.size() != kColumnsBeforeCovered)
    throw Error("expected " + std::to_string(kColumns) + " fields, found " + std::to_string(f.size()));
  try {
    SuiteRow r;
    r.experiment = f[0];
    r.setting = to_int(f[1]);
    r.lidar = f[2];
    r.noise_k = to_double(f[3]);
    r.frames = to_int(f[4]);
    r.preset = f[5];
    std::size_t used = 0;
    r.seed = std::stoull(f[6], &used);
    if (used != f[6].size()) throw Error("bad seed '" + f[6] + "'");
    r.repetition = to_int(f[7]);
    if (f[8] != "0" && f[8] != "1") throw Error("success must be 0 or 1");
    r.success = f[8] == "1";
    r.reason = f[9];
    r.e_t = to_double(f[10]);
    r.e_r = to_double(f[11]);
    r.lidar_frames = to_int(f[12]);
    r.camera_frames = to_int(f[13]);
    r.wall_s = to_double(f[14]);
    r.scene = f[15];
    r.verdict = f[16];
    if (f.size() > kColumnsBeforeCovered) r.covered = to_int(f[17]);
    if (f.size() > kColumnsBeforeReasons) r.check_reasons = f[18];
    if (f.size() > kColumnsBeforeCentres) {
      r.e_lidar_centres = to_double(f[19]);
      r.e_camera_centres = to_double(f[20]);
    }
    if (f.size() > kColumnsBeforeBounds) {
      r.bound_t = to_double(f[21]);
      r.bound_r = to_double(f[22]);
    }
    if (f.size() > kColumnsBeforeDraws) {
      r.face = f[23];
      r.markers = f[24];
      r.roll = to_double(f[25]) * M_PI / 180.0;
      r.lens = f[26];
    }
    return r;
  } catch (const std::logic_error& error) {  // std::stoi and friends
    throw Error(std::string("bad number (") + error.what() + ")");
  }
}

SuiteCsv read_suite_csv(const std::string& path) {
  SuiteCsv csv;
  std::ifstream in(path, std::ios::binary);
  if (!in) return csv;
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  if (text.empty()) return csv;

  std::size_t begin = 0;
  int line_number = 0;
  while (begin < text.size()) {
    const std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) {  // interrupted while writing this line
      csv.trimmed = true;
      break;
    }
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    if (++line_number == 1) {
      if (line != kHeader) throw FileError(path, "not a results.csv of l2s suite (unexpected header)");
      continue;
    }
    if (line.empty()) continue;
    try {
      csv.rows.push_back(parse_csv_line(line));
    } catch (const Error& error) {
      throw FileError(path, "line " + std::to_string(line_number) + ": " + error.what());
    }
  }
  return csv;
}

void write_suite_csv(const std::string& path, const std::vector<SuiteRow>& rows) {
  detail::write_file_atomically(path, [&](std::ostream& out) {
    out << kHeader << '\n';
    for (const auto& row : rows) out << to_csv_line(row) << '\n';
  });
}

SuiteResume resume_suite(const std::vector<SuiteGroup>& plan, const std::vector<SuiteRow>& rows) {
  std::map<std::string, const SuiteCell*> cells;
  for (const auto& group : plan)
    for (const auto& cell : group.cells) cells[cell.key()] = &cell;

  std::map<std::string, std::set<int>> frames_seen;
  for (const auto& row : rows) {
    const auto found = cells.find(row.cell_key());
    if (found == cells.end()) continue;
    if (row.seed != found->second->seed)
      throw Error("results.csv holds cell " + row.cell_key() + " with seed " + std::to_string(row.seed) +
                  ", the plan has " + std::to_string(found->second->seed) +
                  " (another --seed? use another folder)");
    frames_seen[row.cell_key()].insert(row.frames);
  }
  SuiteResume resume;
  for (const auto& [key, frames] : frames_seen)
    if (static_cast<int>(frames.size()) >= cells.at(key)->rows()) resume.done.insert(key);
  for (const auto& row : rows) {
    const std::string key = row.cell_key();
    if (!cells.count(key) || resume.done.count(key))
      resume.kept.push_back(row);
    else
      ++resume.dropped;
  }
  return resume;
}

void sort_suite_rows(std::vector<SuiteRow>& rows) {
  const auto experiment_rank = [](const std::string& name) {
    static const std::vector<std::string> order = {"quick", "frames", "noise", "lidars", "scenes"};
    const auto at = std::find(order.begin(), order.end(), name);
    return static_cast<int>(at - order.begin());
  };
  std::stable_sort(rows.begin(), rows.end(), [&](const SuiteRow& a, const SuiteRow& b) {
    return std::make_tuple(experiment_rank(a.experiment), a.experiment, a.setting, a.lidar, a.noise_k,
                           a.preset, a.repetition, a.frames) <
           std::make_tuple(experiment_rank(b.experiment), b.experiment, b.setting, b.lidar, b.noise_k,
                           b.preset, b.repetition, b.frames);
  });
}

}  // namespace l2s::sim
