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
  }
  return out;
}

Packing read_packing_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot open packing file");
  Packing p;
  std::string text;
  std::size_t line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    const char* c = text.data();
    const char* end = c + text.size();
    double v[3];
    int count = 0;
    while (true) {
      while (c != end && is_space(*c)) ++c;
      if (c == end) break;
      if (count == 3) fail(path, line_no, "more than three numbers (expected x_m y_m radius_m)");
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
    if (count != 3) fail(path, line_no, "expected three numbers x_m y_m radius_m");
    if (!std::isfinite(v[0]) || !std::isfinite(v[1])) fail(path, line_no, "non-finite position");
    if (!std::isfinite(v[2]) || !(v[2] > 0.0)) fail(path, line_no, "radius_m must be positive");
    p.x_m.push_back(v[0]);
    p.y_m.push_back(v[1]);
    p.radius_m.push_back(v[2]);
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
  bool ok = std::fprintf(f, "# x_m y_m radius_m (%zu discs)\n", packing.size()) > 0;
  for (std::size_t i = 0; ok && i < packing.size(); ++i) {
    ok = std::fprintf(f, "%.17g %.17g %.17g\n", packing.x_m[i], packing.y_m[i],
                      packing.radius_m[i]) > 0;
  }
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) throw std::runtime_error(path.string() + ": write error");
}

}  // namespace rockcut::dem
