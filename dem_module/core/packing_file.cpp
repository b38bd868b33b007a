#include "core/packing_file.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <numeric>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

namespace rockcut::dem {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, std::size_t line, const std::string& why) {
  throw std::runtime_error(path.string() + ":" + std::to_string(line) + ": " + why);
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

}  // namespace

Packing in_cell_order(const Packing& packing) {
  const std::size_t n = packing.size();
  if (n == 0) return packing;
  const double cell_m = 2.0 * *std::max_element(packing.radius_m.begin(), packing.radius_m.end());
  const auto [x_lo, x_hi] = std::minmax_element(packing.x_m.begin(), packing.x_m.end());
  const double y_lo = *std::min_element(packing.y_m.begin(), packing.y_m.end());
  const auto ncols = static_cast<std::int64_t>((*x_hi - *x_lo) / cell_m) + 1;
  std::vector<std::int64_t> cell(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto col = static_cast<std::int64_t>((packing.x_m[i] - *x_lo) / cell_m);
    const auto row = static_cast<std::int64_t>((packing.y_m[i] - y_lo) / cell_m);
    cell[i] = row * ncols + std::min(col, ncols - 1);
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cell[a] < cell[b]; });
  Packing out;
  out.x_m.reserve(n);
  out.y_m.reserve(n);
  out.radius_m.reserve(n);
  for (std::size_t i : order) {
    out.x_m.push_back(packing.x_m[i]);
    out.y_m.push_back(packing.y_m[i]);
    out.radius_m.push_back(packing.radius_m[i]);
    if (packing.has_motion()) {
      out.vx_m_s.push_back(packing.vx_m_s[i]);
      out.vy_m_s.push_back(packing.vy_m_s[i]);
      out.omega_rad_s.push_back(packing.omega_rad_s[i]);
    }
  }
  return out;
}

Packing read_packing_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot open packing file");
  Packing p;
  std::string text;
  std::size_t line_no = 0;
  bool motion = false;  // a line so far gave a velocity (has_motion() is false until a push)
  while (std::getline(in, text)) {
    ++line_no;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    const char* c = text.data();
    const char* end = c + text.size();
    double v[6];
    int count = 0;
    while (true) {
      while (c != end && is_space(*c)) ++c;
      if (c == end) break;
      if (count == 6) {
        fail(path, line_no,
             "more than six numbers (expected x_m y_m radius_m [vx_m_s vy_m_s [omega_rad_s]])");
      }
      if (*c == '+') ++c;  // from_chars does not take a leading '+'
      const auto [ptr, ec] = std::from_chars(c, end, v[count]);
      if (ec != std::errc() || (ptr != end && !is_space(*ptr))) {
        // The text is not quoted: the error may go to a peer that may not read the file.
        fail(path, line_no, "not a number (value " + std::to_string(count + 1) + " of x_m y_m radius_m)");
      }
      ++count;
      c = ptr;
    }
    if (count == 0) continue;
    if (count != 3 && count != 5 && count != 6) {
      fail(path, line_no,
           std::to_string(count) + " numbers; expected 3 (x_m y_m radius_m), 5 (and vx_m_s vy_m_s) "
           "or 6 (and omega_rad_s)");
    }
    if (!std::isfinite(v[0]) || !std::isfinite(v[1])) fail(path, line_no, "non-finite position");
    if (!std::isfinite(v[2]) || !(v[2] > 0.0)) fail(path, line_no, "radius_m must be positive");
    for (int k = 3; k < count; ++k) {
      if (!std::isfinite(v[k])) {
        fail(path, line_no, std::string("non-finite ") + (k == 5 ? "omega_rad_s" : "velocity"));
      }
    }
    if (count > 3 && !motion) {  // the first line with motion: zeros for the earlier discs
      motion = true;
      p.vx_m_s.assign(p.size(), 0.0);
      p.vy_m_s.assign(p.size(), 0.0);
      p.omega_rad_s.assign(p.size(), 0.0);
    }
    p.x_m.push_back(v[0]);
    p.y_m.push_back(v[1]);
    p.radius_m.push_back(v[2]);
    if (motion) {
      p.vx_m_s.push_back(count > 3 ? v[3] : 0.0);
      p.vy_m_s.push_back(count > 3 ? v[4] : 0.0);
      p.omega_rad_s.push_back(count > 5 ? v[5] : 0.0);
    }
  }
  if (in.bad()) throw std::runtime_error(path.string() + ": read error");
  return p;
}

void write_packing_file(const std::filesystem::path& path, const Packing& packing) {
  if (packing.x_m.size() != packing.size() || packing.y_m.size() != packing.size()) {
    throw std::invalid_argument("write_packing_file: x_m, y_m and radius_m differ in size");
  }
  std::FILE* f = std::fopen(path.string().c_str(), "w");
  if (!f) throw std::runtime_error(path.string() + ": cannot write packing file");
  const bool motion = packing.has_motion();
  bool ok = std::fprintf(f, "# x_m y_m radius_m%s (%zu discs)\n",
                         motion ? " vx_m_s vy_m_s omega_rad_s" : "", packing.size()) > 0;
  for (std::size_t i = 0; ok && i < packing.size(); ++i) {
    ok = motion ? std::fprintf(f, "%.17g %.17g %.17g %.17g %.17g %.17g\n", packing.x_m[i],
                               packing.y_m[i], packing.radius_m[i], packing.vx_m_s[i],
                               packing.vy_m_s[i], packing.omega_rad_s[i]) > 0
                : std::fprintf(f, "%.17g %.17g %.17g\n", packing.x_m[i], packing.y_m[i],
                               packing.radius_m[i]) > 0;
  }
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) throw std::runtime_error(path.string() + ": write error");
}

}  // namespace rockcut::dem
