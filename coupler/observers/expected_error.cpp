#include "observers/expected_error.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <span>
#include <sstream>
#include <stdexcept>

namespace rockcut::coupler {

namespace {

// The reduced scene's mean radius, the size ladder's 1 (the study's scene, not a table entry).
constexpr double kStudyMeanRadiusM = 1.2e-3;

[[noreturn]] void bad(const std::filesystem::path& csv, int line, const std::string& problem) {
  throw std::runtime_error(csv.string() + ":" + std::to_string(line) + ": " + problem);
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) {
    while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\r')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(cell.begin());
    cells.push_back(cell);
  }
  return cells;
}

double parse_number(const std::string& text, const std::filesystem::path& csv, int line,
                    const std::string& column) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    bad(csv, line, column + " \"" + text + "\" is not a number");
  return value;
}

// The error at `value`, linear in log(value) between the ladder's settings. A value finer than the
// finest gets the finest's error (the study cannot resolve it); coarser than the coarsest: none.
std::optional<double> interpolate(std::span<const LadderPoint> ladder, double value) {
  const bool descending = ladder.front().value > ladder.back().value;
  const auto coarser = [&](double a, double b) { return descending ? a > b : a < b; };
  if (coarser(value, ladder.front().value * (1 + 1e-9))) return std::nullopt;
  if (!coarser(value, ladder.back().value)) return ladder.back().force_error;
  for (std::size_t k = 0; k + 1 < ladder.size(); ++k) {
    const LadderPoint& a = ladder[k];
    const LadderPoint& b = ladder[k + 1];
    if (coarser(value, b.value) && !coarser(value, a.value * (1 + 1e-9))) {
      const double s = std::log(value / a.value) / std::log(b.value / a.value);
      return a.force_error + s * (b.force_error - a.force_error);
    }
  }
  return std::nullopt;
}

std::string percent(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.0f %%", 100 * v);
  return b;
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

}  // namespace

std::filesystem::path error_model_path(const std::filesystem::path& program_dir) {
  return program_dir.parent_path() / "share" / "rockcut" / "expected_error.csv";
}

std::optional<ErrorModel> read_error_model(const std::filesystem::path& csv,
                                           const std::string& damping,
                                           std::vector<std::string>* studied,
                                           const std::string& fluid_force) {
  std::ifstream in(csv);
  if (!in) bad(csv, 0, std::string("cannot read the accuracy study's table: ") + std::strerror(errno));
  ErrorModel model;
  const std::pair<const char*, std::vector<LadderPoint>*> ladders[] = {
      {"dt_safety", &model.dt_safety},
      {"fluid_step_ratio", &model.fluid_step_ratio},
      {"h_per_diameter", &model.h_per_diameter},
      {"size_scale", &model.size_scale}};
  int column_ladder = -1, column_value = -1, column_error = -1, column_damping = -1,
      column_force = -1, column_fluid_force = -1;
  std::vector<std::string> models;
  int rows_of_damping = 0, line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = split_csv(line);
    if (column_ladder < 0) {  // the header
      for (int c = 0; c < static_cast<int>(cells.size()); ++c) {
        if (cells[c] == "ladder") column_ladder = c;
        if (cells[c] == "value") column_value = c;
        if (cells[c] == "force_error") column_error = c;
        if (cells[c] == "damping") column_damping = c;
        if (cells[c] == "force") column_force = c;
        if (cells[c] == "fluid_force") column_fluid_force = c;
      }
      if (column_ladder < 0 || column_value < 0 || column_error < 0)
        bad(csv, line_no, "the header must name the columns ladder, value and force_error");
      continue;
    }
    const int needed = std::max({column_ladder, column_value, column_error, column_damping,
                                 column_force, column_fluid_force});
    if (static_cast<int>(cells.size()) <= needed)
      bad(csv, line_no, "expected " + std::to_string(needed + 1) + " columns or more");
    const std::string row_damping = column_damping < 0 ? "local" : cells[column_damping];
    if (std::find(models.begin(), models.end(), row_damping) == models.end())
      models.push_back(row_damping);
    const std::string force = column_force < 0 ? "mean" : cells[column_force];
    if (force != "mean" && force != "peak")
      bad(csv, line_no, "unknown force \"" + force + "\": mean or peak");
    const auto ladder = std::find_if(std::begin(ladders), std::end(ladders),
                                     [&](const auto& l) { return cells[column_ladder] == l.first; });
    if (ladder == std::end(ladders))
      bad(csv, line_no, "unknown ladder \"" + cells[column_ladder] +
                            "\": one of dt_safety, fluid_step_ratio, h_per_diameter, size_scale");
    const LadderPoint point{parse_number(cells[column_value], csv, line_no, "value"),
                            parse_number(cells[column_error], csv, line_no, "force_error")};
    if (point.value <= 0.0 || point.force_error < 0.0)
      bad(csv, line_no, "a setting must be > 0 and its error >= 0");
    // How the fluid's force is applied between exchanges matters only to the lag's ladder.
    const std::string row_fluid_force =
        column_fluid_force < 0 ? "held" : cells[column_fluid_force];
    if (row_fluid_force != "held" && row_fluid_force != "extrapolated" &&
        row_fluid_force != "extrapolated+passivity")
      bad(csv, line_no,
          "unknown fluid_force \"" + row_fluid_force +
              "\": held, extrapolated or extrapolated+passivity");
    if (row_fluid_force != "held" && ladder->second != &model.fluid_step_ratio)
      bad(csv, line_no, "fluid_force \"" + row_fluid_force + "\" on the ladder " +
                            ladder->first + ": only fluid_step_ratio depends on it");
    if (row_damping != damping) continue;
    if (ladder->second == &model.fluid_step_ratio && row_fluid_force != fluid_force) continue;
    if (rows_of_damping++ == 0) {
      model.force = force;
    } else if (force != model.force) {
      bad(csv, line_no, "force \"" + force + "\" where the rows of damping \"" + damping +
                            "\" before it have \"" + model.force + "\"");
    }
    std::vector<LadderPoint>& points = *ladder->second;
    if (!points.empty() && !(point.value < points.back().value))
      bad(csv, line_no, std::string(ladder->first) + ": settings go from the coarsest (largest) "
                        "to the finest (smallest)");
    points.push_back(point);
  }
  if (column_ladder < 0) bad(csv, line_no, "the header must name the columns ladder, value and force_error");
  if (rows_of_damping == 0) {
    if (studied) *studied = models;
    return std::nullopt;
  }
  for (const auto& [name, points] : ladders) {
    // A fluid_force the study has no ladder for leaves the lag's ladder empty: not covered.
    if (points == &model.fluid_step_ratio && fluid_force != "held" && points->empty()) continue;
    if (points->size() < 2)
      bad(csv, line_no, std::string("the ladder ") + name + " needs two settings or more");
  }
  return model;
}

std::optional<double> expected_force_error(const ErrorModel& model, const CutSettings& s,
                                           std::string* detail) {
  struct Part {
    const char* name;
    std::span<const LadderPoint> ladder;
    double value;
  };
  const Part parts[] = {{"dt_safety", model.dt_safety, s.dt_safety},
                        {"fluid step / stiffness limit", model.fluid_step_ratio, s.fluid_step_ratio},
                        {"h / mean diameter", model.h_per_diameter, s.h_per_diameter},
                        {"disc size / reduced scene's", model.size_scale, s.size_scale}};
  double sum2 = 0.0;
  std::string text;
  for (const Part& p : parts) {
    if (p.ladder.empty()) {
      if (detail)
        *detail = std::string(p.name) +
                  ": no measurement with this coupling.fluid_force and lag_correction";
      return std::nullopt;
    }
    const std::optional<double> e = interpolate(p.ladder, p.value);
    if (!e) {
      if (detail) {
        *detail = std::string(p.name) + " = " + number(p.value) +
                  " is coarser than the study covers (" + number(p.ladder.front().value) + ")";
      }
      return std::nullopt;
    }
    sum2 += *e * *e;
    text += (text.empty() ? "" : ", ") + percent(*e) + " from " + p.name + " " + number(p.value);
  }
  if (detail) *detail = text;
  return std::sqrt(sum2);
}

std::optional<std::string> expected_error_line(const rockcut::Scene& scene, const TimePlan& plan,
                                               double dem_limit_s, double fluid_stiffness_limit_s,
                                               const std::filesystem::path& program_dir) {
  if (!scene.has_fluid() || !scene.dem().has_tool() || !scene.dem().has_specimen()) {
    return std::nullopt;
  }
  // Each damping model's force is another quantity (docs/model.md, "Damping"): its own rows.
  const std::string& damping = scene.dem().damping().model();
  std::optional<ErrorModel> model;
  std::vector<std::string> studied;
  try {
    model = read_error_model(error_model_path(program_dir), damping, &studied,
                             !plan.extrapolate_fluid_force ? "held"
                             : plan.lag_passivity          ? "extrapolated+passivity"
                                                           : "extrapolated");
  } catch (const std::runtime_error& e) {
    return std::string("accuracy   no estimate: ") + e.what();
  }
  if (!model) {
    std::string names;
    for (const std::string& name : studied) names += (names.empty() ? "\"" : ", \"") + name + "\"";
    return "accuracy   not covered by the work-precision study (docs/accuracy.md): it measured "
           "dem.damping.model " + names + ", not \"" + damping + "\"";
  }
  const rockcut::Specimen& sp = scene.dem().specimen();
  CutSettings s;
  s.dt_safety = dem_limit_s > 0 ? plan.dt_s / dem_limit_s : 0.0;
  s.fluid_step_ratio = plan.coupling_interval > 1 && fluid_stiffness_limit_s > 0
                           ? plan.coupling_interval * plan.dt_s / fluid_stiffness_limit_s
                           : 0.0;
  s.h_per_diameter = scene.fluid().smoothing_length_m() / (sp.radius_min_m() + sp.radius_max_m());
  s.size_scale = 0.5 * (sp.radius_min_m() + sp.radius_max_m()) / kStudyMeanRadiusM;
  std::string detail;
  const std::optional<double> e = expected_force_error(*model, s, &detail);
  if (!e) return "accuracy   not covered by the work-precision study (docs/accuracy.md): " + detail;
  return "accuracy   expected error of the " + model->force + " horizontal force about " +
         percent(*e) + " (root sum square of " + detail +
         "; docs/accuracy.md, against the study's finest settings)";
}

}  // namespace rockcut::coupler
