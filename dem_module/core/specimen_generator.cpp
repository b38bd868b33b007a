// Advancing-front packing of discs (Feng, Han & Owen 2003). See specimen_generator.hpp.
//
// The front is a closed counter-clockwise loop of discs (a doubly linked list over disc indices);
// the region lies outside it. Each step takes the front disc A of smallest "distance" from the centre
// (a min-heap with lazy deletion) and its successor B, and places a new disc C touching both on the
// outer side (to the right of A -> B). If C overlaps a front disc D, the part of the front between
// A (or B) and D is closed off and C is re-placed against D with the same radius; if C cannot be
// placed (A and B too far apart, or C overlaps a disc no longer on the front) A leaves the front.
// Every retry removes at least one front disc and every success adds one disc, so the loop ends.
//
// The distance is shaped like the region so the front grows like it: max(|x|/Hx, |y|/Hy) for a
// rectangle, |p|/Hr for a circle, where H* are the region's half sizes grown by 2 r_max. Growth stops
// when every front disc is beyond 1, so the region is covered; only discs entirely inside the region
// are kept.
#include "core/specimen_generator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/specimen_grid.hpp"

namespace rockcut::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// Refuse specimens that would not fit in memory sensibly (and int32 disc indices).
constexpr double kMaxDiscs = 5.0e7;

[[noreturn]] void bad(const std::string& what) {
  throw std::invalid_argument("PackingSpec: " + what);
}

void require_positive(double v, const char* field) {
  if (!std::isfinite(v) || !(v > 0.0)) {
    bad(std::string(field) + " must be positive and finite (got " + std::to_string(v) + ")");
  }
}

double region_area(const PackingRegion& g) {
  return g.shape == PackingRegion::Shape::circle ? kPi * g.radius_m * g.radius_m
                                                 : g.width_m * g.height_m;
}

void validate(const PackingSpec& s) {
  const PackingRegion& g = s.region;
  if (g.shape != PackingRegion::Shape::rectangle && g.shape != PackingRegion::Shape::circle) {
    bad("region.shape is neither rectangle nor circle");
  }
  if (!std::isfinite(g.center_x_m)) bad("region.center_x_m must be finite");
  if (!std::isfinite(g.center_y_m)) bad("region.center_y_m must be finite");
  require_positive(s.radius_min_m, "radius_min_m");
  require_positive(s.radius_max_m, "radius_max_m");
  if (s.radius_min_m > s.radius_max_m) {
    bad("radius_min_m > radius_max_m (" + std::to_string(s.radius_min_m) + " > " +
        std::to_string(s.radius_max_m) + ")");
  }
  const double d = 2.0 * s.radius_max_m;
  if (g.shape == PackingRegion::Shape::rectangle) {
    require_positive(g.width_m, "region.width_m");
    require_positive(g.height_m, "region.height_m");
    if (g.width_m < d) bad("region.width_m is smaller than a disc (2 * radius_max_m)");
    if (g.height_m < d) bad("region.height_m is smaller than a disc (2 * radius_max_m)");
  } else {
    require_positive(g.radius_m, "region.radius_m");
    if (g.radius_m < s.radius_max_m) bad("region.radius_m is smaller than a disc (radius_max_m)");
  }
  const double rm = 0.5 * (s.radius_min_m + s.radius_max_m);
  if (region_area(g) / (kPi * rm * rm) > kMaxDiscs) {
    bad("region / radius_min_m, radius_max_m: more than 5e7 discs would be needed");
  }
}

/// Radii uniform in [lo, lo + span]: the top 53 bits of mt19937_64 as a double in [0, 1). Exact and
/// portable (std::uniform_real_distribution's output is implementation-defined).
class RadiusSource {
 public:
  RadiusSource(std::uint64_t seed, double lo, double hi) : rng_(seed), lo_(lo), span_(hi - lo) {}
  double next() { return lo_ + span_ * static_cast<double>(rng_() >> 11) * 0x1.0p-53; }

 private:
  std::mt19937_64 rng_;
  double lo_, span_;
};

/// Centre of a disc of radius r touching discs a and b, on the right of a -> b (left if !right).
/// False if there is none (a and b too far apart, or concentric).
bool touching_position(double xa, double ya, double ra, double xb, double yb, double rb, double r,
                       bool right, double& xc, double& yc) {
  const double dx = xb - xa, dy = yb - ya;
  const double d2 = dx * dx + dy * dy;
  const double d = std::sqrt(d2);
  const double la = ra + r, lb = rb + r;
  if (!(d > 0.0) || d > la + lb) return false;
  const double s = (la * la - lb * lb + d2) / (2.0 * d);  // along a -> b from a
  const double h2 = la * la - s * s;
  if (!(h2 >= 0.0)) return false;  // |la - lb| > d: impossible for non-overlapping a, b
  const double h = std::sqrt(h2);
  const double ex = dx / d, ey = dy / d;
  const double nx = right ? ey : -ey, ny = right ? -ex : ex;
  xc = xa + s * ex + h * nx;
  yc = ya + s * ey + h * ny;
  return true;
}

class FrontPacker {
 public:
  explicit FrontPacker(const PackingSpec& spec)
      : rmax_(spec.radius_max_m),
        tol_(0.25 * packing_overlap_tolerance_m(spec)),
        radii_(spec.seed, spec.radius_min_m, spec.radius_max_m),
        grid_(make_grid(spec)) {
    const PackingRegion& g = spec.region;
    if (g.shape == PackingRegion::Shape::circle) {
      circle_ = true;
      inv_hx_ = inv_hy_ = 1.0 / (g.radius_m + 2.0 * rmax_);
    } else {
      inv_hx_ = 1.0 / (0.5 * g.width_m + 2.0 * rmax_);
      inv_hy_ = 1.0 / (0.5 * g.height_m + 2.0 * rmax_);
    }
    const double rm = 0.5 * (spec.radius_min_m + spec.radius_max_m);
    const double grown = circle_ ? kPi / (inv_hx_ * inv_hx_) : 4.0 / (inv_hx_ * inv_hy_);
    const auto expected = static_cast<std::size_t>(grown / (kPi * rm * rm));
    x_.reserve(expected);
    y_.reserve(expected);
    r_.reserve(expected);
  }

  /// Grows the packing; returns centres relative to the region centre.
  void run() {
    seed_triangle();
    // Safety net only: the loop provably ends (see the file comment) long before this.
    const std::size_t max_steps = 64 * (x_.capacity() + 16);
    std::size_t steps = 0;
    while (!heap_.empty() && heap_.top().first <= 1.0 && front_size_ >= 3) {
      if (++steps > max_steps) throw std::logic_error("generate_packing: front did not terminate");
      const std::int32_t popped = heap_.top().second;
      heap_.pop();
      if (!on_front_[static_cast<std::size_t>(popped)]) continue;  // lazy deletion
      advance(popped);
      if (on_front_[static_cast<std::size_t>(popped)]) push(popped);
    }
  }

  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& y() const { return y_; }
  const std::vector<double>& r() const { return r_; }

 private:
  using Entry = std::pair<double, std::int32_t>;

  static detail::DiscGrid make_grid(const PackingSpec& s) {
    const PackingRegion& g = s.region;
    const double m = 4.0 * s.radius_max_m;
    const double hx = (g.shape == PackingRegion::Shape::circle ? g.radius_m : 0.5 * g.width_m) + m;
    const double hy = (g.shape == PackingRegion::Shape::circle ? g.radius_m : 0.5 * g.height_m) + m;
    return detail::DiscGrid(-hx, -hy, hx, hy, 2.0 * s.radius_max_m);
  }

  double key(std::int32_t i) const {
    const double x = x_[static_cast<std::size_t>(i)], y = y_[static_cast<std::size_t>(i)];
    if (circle_) return std::sqrt(x * x + y * y) * inv_hx_;
    return std::max(std::fabs(x) * inv_hx_, std::fabs(y) * inv_hy_);
  }

  void push(std::int32_t i) { heap_.emplace(key(i), i); }

  std::int32_t add_disc(double x, double y, double r) {
    const auto i = static_cast<std::int32_t>(r_.size());
    x_.push_back(x);
    y_.push_back(y);
    r_.push_back(r);
    next_.push_back(-1);
    prev_.push_back(-1);
    on_front_.push_back(0);
    grid_.insert(i, x, y);
    return i;
  }

  double take_radius() {
    if (!has_pending_) {
      pending_ = radii_.next();
      has_pending_ = true;
    }
    return pending_;
  }

  void link(std::int32_t a, std::int32_t b) {
    next_[static_cast<std::size_t>(a)] = b;
    prev_[static_cast<std::size_t>(b)] = a;
  }

  /// Takes the front discs strictly between a and b (walking forward) off the front; links a -> b.
  void close_between(std::int32_t a, std::int32_t b) {
    for (std::int32_t k = next_[static_cast<std::size_t>(a)]; k != b;) {
      const std::int32_t n = next_[static_cast<std::size_t>(k)];
      on_front_[static_cast<std::size_t>(k)] = 0;
      --front_size_;
      k = n;
    }
    link(a, b);
  }

  void seed_triangle() {
    const double r0 = take_radius();
    has_pending_ = false;
    const double r1 = take_radius();
    has_pending_ = false;
    const double r2 = take_radius();
    has_pending_ = false;
    const double x1 = r0 + r1;
    double x2 = 0.0, y2 = 0.0;
    touching_position(0.0, 0.0, r0, x1, 0.0, r1, r2, /*right=*/false, x2, y2);
    // Centre the triangle on the region centre (a translation keeps the contacts up to round-off).
    const double sx = (x1 + x2) / 3.0, sy = y2 / 3.0;
    const std::int32_t a = add_disc(0.0 - sx, 0.0 - sy, r0);
    const std::int32_t b = add_disc(x1 - sx, 0.0 - sy, r1);
    const std::int32_t c = add_disc(x2 - sx, y2 - sy, r2);  // left of a -> b: a, b, c is CCW
    link(a, b);
    link(b, c);
    link(c, a);
    for (std::int32_t i : {a, b, c}) {
      on_front_[static_cast<std::size_t>(i)] = 1;
      push(i);
    }
    front_size_ = 3;
  }

  /// A leaves the front: prev(A) -> next(A).
  void drop(std::int32_t a) {
    link(prev_[static_cast<std::size_t>(a)], next_[static_cast<std::size_t>(a)]);
    on_front_[static_cast<std::size_t>(a)] = 0;
    --front_size_;
  }

  /// One new disc against front disc a (or a retry chain that ends with a leaving the front).
  void advance(std::int32_t a) {
    std::int32_t b = next_[static_cast<std::size_t>(a)];
    const double r = take_radius();
    while (true) {
      if (front_size_ < 3) return;  // degenerate front: run() stops
      const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
      double xc = 0.0, yc = 0.0;
      if (!touching_position(x_[ua], y_[ua], r_[ua], x_[ub], y_[ub], r_[ub], r, true, xc, yc)) {
        drop(a);
        return;
      }
      bool blocked_inside = false;
      candidates_.clear();
      grid_.for_each_near(xc, yc, [&](std::int32_t j) {
        if (j == a || j == b) return true;
        const auto uj = static_cast<std::size_t>(j);
        const double dx = x_[uj] - xc, dy = y_[uj] - yc;
        const double reach = r + r_[uj] - tol_;
        if (dx * dx + dy * dy >= reach * reach) return true;
        if (!on_front_[uj]) {
          blocked_inside = true;
          return false;
        }
        candidates_.push_back(j);
        return true;
      });
      if (blocked_inside) {
        drop(a);
        return;
      }
      if (candidates_.empty()) {
        const std::int32_t c = add_disc(xc, yc, r);
        has_pending_ = false;
        link(a, c);
        link(c, b);
        on_front_[static_cast<std::size_t>(c)] = 1;
        ++front_size_;
        push(c);
        return;
      }
      // The overlapped front disc nearest along the front; ahead of A wins ties.
      std::int32_t fwd = b, bwd = a;
      std::int32_t d = -1;
      bool ahead = true;
      for (std::size_t step = 0; step < front_size_ && d < 0; ++step) {
        fwd = next_[static_cast<std::size_t>(fwd)];
        bwd = prev_[static_cast<std::size_t>(bwd)];
        for (std::int32_t cand : candidates_) {
          if (cand == fwd) {
            d = cand;
            ahead = true;
            break;
          }
          if (cand == bwd) {
            d = cand;
            ahead = false;
            break;
          }
        }
      }
      if (d < 0) {  // cannot happen for a consistent front; be robust anyway
        drop(a);
        return;
      }
      if (ahead) {
        close_between(a, d);  // B and what follows it up to D are enclosed
        b = d;
      } else {
        close_between(d, b);  // A and what precedes it back to D are enclosed
        a = d;
      }
    }
  }

  double rmax_, tol_;
  bool circle_ = false;
  double inv_hx_ = 0, inv_hy_ = 0;
  RadiusSource radii_;
  double pending_ = 0;
  bool has_pending_ = false;
  detail::DiscGrid grid_;
  std::vector<double> x_, y_, r_;
  std::vector<std::int32_t> next_, prev_;
  std::vector<std::uint8_t> on_front_;
  std::size_t front_size_ = 0;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap_;
  std::vector<std::int32_t> candidates_;
};

}  // namespace

double packing_overlap_tolerance_m(const PackingSpec& spec) {
  const PackingRegion& g = spec.region;
  const double extent = g.shape == PackingRegion::Shape::circle ? 2.0 * g.radius_m
                                                                : g.width_m + g.height_m;
  const double scale = std::fabs(g.center_x_m) + std::fabs(g.center_y_m) + extent;
  return 64.0 * std::numeric_limits<double>::epsilon() * scale;
}

Packing generate_packing(const PackingSpec& spec) {
  validate(spec);
  FrontPacker packer(spec);
  packer.run();

  const PackingRegion& g = spec.region;
  const bool circle = g.shape == PackingRegion::Shape::circle;
  const double cx = g.center_x_m, cy = g.center_y_m;
  const double hx = circle ? g.radius_m : 0.5 * g.width_m;
  const double hy = circle ? g.radius_m : 0.5 * g.height_m;

  // Keep the discs entirely inside the region, tested on the returned (global) coordinates.
  struct Kept {
    std::int64_t cell;
    std::size_t index;
    double x, y, r;
  };
  std::vector<Kept> kept;
  kept.reserve(packer.r().size());
  const double cell = 2.0 * spec.radius_max_m;
  const double x_lo = cx - hx, y_lo = cy - hy;
  const auto ncols = static_cast<std::int64_t>(std::ceil(2.0 * hx / cell)) + 1;
  for (std::size_t i = 0; i < packer.r().size(); ++i) {
    const double x = cx + packer.x()[i], y = cy + packer.y()[i], r = packer.r()[i];
    const double dx = x - cx, dy = y - cy;
    const bool inside = circle ? std::sqrt(dx * dx + dy * dy) + r <= g.radius_m
                               : std::fabs(dx) + r <= hx && std::fabs(dy) + r <= hy;
    if (!inside) continue;
    const auto col = std::clamp<std::int64_t>(static_cast<std::int64_t>((x - x_lo) / cell), 0,
                                              ncols - 1);
    const auto row = std::max<std::int64_t>(static_cast<std::int64_t>((y - y_lo) / cell), 0);
    kept.push_back({row * ncols + col, i, x, y, r});
  }
  // Row-major cell order (y rows, x within a row): neighbours end up close in memory.
  std::sort(kept.begin(), kept.end(), [](const Kept& a, const Kept& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.index < b.index;
  });

  Packing out;
  out.x_m.reserve(kept.size());
  out.y_m.reserve(kept.size());
  out.radius_m.reserve(kept.size());
  for (const Kept& k : kept) {
    out.x_m.push_back(k.x);
    out.y_m.push_back(k.y);
    out.radius_m.push_back(k.r);
  }
  return out;
}

}  // namespace rockcut::dem
