#include "geometry/outline_order.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace relief::detail {
namespace {

struct Segment {
  Vec2 a, b;
};

double orient(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

bool on_segment(const Vec2& p, const Segment& s) {
  return std::min(s.a.x(), s.b.x()) <= p.x() && p.x() <= std::max(s.a.x(), s.b.x()) &&
         std::min(s.a.y(), s.b.y()) <= p.y() && p.y() <= std::max(s.a.y(), s.b.y());
}

// Whether two segments share any point (touching counts).
bool touch(const Segment& s, const Segment& t) {
  const double d1 = orient(t.a, t.b, s.a), d2 = orient(t.a, t.b, s.b);
  const double d3 = orient(s.a, s.b, t.a), d4 = orient(s.a, s.b, t.b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && on_segment(s.a, t)) || (d2 == 0 && on_segment(s.b, t)) ||
         (d3 == 0 && on_segment(t.a, s)) || (d4 == 0 && on_segment(t.b, s));
}

// Whether two consecutive segments (s ending where t starts) fold back onto each other.
bool fold(const Segment& s, const Segment& t) {
  const Vec2 u = s.b - s.a, v = t.b - t.a;
  return orient(s.a, s.b, t.b) == 0.0 && u.dot(v) < 0.0;
}

class Search {
 public:
  Search(const std::vector<Polyline2>& chains, std::size_t budget) : chains_(chains), budget_(budget) {}

  std::optional<std::vector<std::size_t>> run() {
    if (chains_.empty()) return std::nullopt;
    used_.assign(chains_.size(), 0);
    used_[0] = 1;
    order_ = {0};
    points_.clear();
    segments_.clear();
    if (!append(chains_[0])) return std::nullopt;
    descend(0.0);
    if (best_.empty()) return std::nullopt;
    return best_;
  }

  // Whether the chains in this order make a simple counter-clockwise polygon.
  bool simple(const std::vector<std::size_t>& order) {
    points_.clear();
    segments_.clear();
    for (const std::size_t k : order) {
      if (k >= chains_.size() || !append(chains_[k])) return false;
    }
    if (points_.size() < 3) return false;
    close(0.0);
    return best_gaps_ < std::numeric_limits<double>::infinity();
  }

 private:
  // Appends a chain's points (joined to the current last point by a gap); false when a new edge
  // touches an earlier one.
  bool append(const Polyline2& chain) {
    for (const Vec2& p : chain) {
      if (!points_.empty() && p == points_.back()) continue;
      if (!points_.empty() && !add_segment({points_.back(), p}, false)) return false;
      points_.push_back(p);
    }
    return true;
  }

  bool add_segment(const Segment& s, bool closing) {
    const std::size_t n = segments_.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (i + 1 == n) {  // shares s.a
        if (fold(segments_[i], s)) return false;
        continue;
      }
      if (closing && i == 0) {  // shares s.b
        if (fold(s, segments_[0])) return false;
        continue;
      }
      if (touch(segments_[i], s)) return false;
    }
    segments_.push_back(s);
    return true;
  }

  void descend(double gaps) {
    if (steps_++ >= budget_ || gaps >= best_gaps_) return;
    if (order_.size() == chains_.size()) {
      close(gaps);
      return;
    }
    // Nearest next ends first: short gaps make a tight outline and a good bound early.
    std::vector<std::pair<double, std::size_t>> next;
    for (std::size_t k = 0; k < chains_.size(); ++k) {
      if (!used_[k] && !chains_[k].empty())
        next.emplace_back((chains_[k].front() - points_.back()).norm(), k);
    }
    std::sort(next.begin(), next.end());
    for (const auto& [gap, k] : next) {
      const std::size_t points = points_.size(), segments = segments_.size();
      if (append(chains_[k])) {
        used_[k] = 1;
        order_.push_back(k);
        descend(gaps + gap);
        order_.pop_back();
        used_[k] = 0;
      }
      points_.resize(points);
      segments_.resize(segments);
      if (steps_ >= budget_) return;
    }
  }

  void close(double gaps) {
    const Vec2& first = points_.front();
    const double gap = (first - points_.back()).norm();
    if (gaps + gap >= best_gaps_) return;
    const std::size_t segments = segments_.size();
    const bool simple = points_.back() == first || add_segment({points_.back(), first}, true);
    segments_.resize(segments);
    if (!simple) return;
    double twice_area = 0.0;
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Vec2& p = points_[i];
      const Vec2& q = points_[(i + 1) % points_.size()];
      twice_area += p.x() * q.y() - q.x() * p.y();
    }
    if (!(twice_area > 0.0)) return;
    best_ = order_;
    best_gaps_ = gaps + gap;
  }

  const std::vector<Polyline2>& chains_;
  std::size_t budget_;
  std::size_t steps_ = 0;
  std::vector<std::uint8_t> used_;
  std::vector<std::size_t> order_, best_;
  double best_gaps_ = std::numeric_limits<double>::infinity();
  Polyline2 points_;
  std::vector<Segment> segments_;
};

}  // namespace

std::optional<std::vector<std::size_t>> simple_outline_order(const std::vector<Polyline2>& chains,
                                                             std::size_t budget) {
  return Search(chains, budget).run();
}

bool is_simple_outline(const std::vector<Polyline2>& chains, const std::vector<std::size_t>& order) {
  return Search(chains, 0).simple(order);
}

std::vector<std::size_t> junction_end_order(const std::vector<PlanEnd>& ends) {
  std::vector<std::size_t> order(ends.size());
  for (std::size_t k = 0; k < ends.size(); ++k) order[k] = k;
  if (ends.size() < 2) return order;
  Vec2 centre = Vec2::Zero();
  for (const PlanEnd& e : ends) centre += 0.5 * (e.right + e.left);
  centre /= static_cast<double>(ends.size());
  double reach = 0.0;
  for (const PlanEnd& e : ends) reach = std::max(reach, (0.5 * (e.right + e.left) - centre).norm());
  std::vector<double> angle(ends.size());
  for (std::size_t k = 0; k < ends.size(); ++k) {
    const Vec2 ahead = 0.5 * (ends[k].right + ends[k].left) + reach * ends[k].out - centre;
    angle[k] = std::atan2(ahead.y(), ahead.x());
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return angle[a] < angle[b]; });
  std::vector<Polyline2> chains;
  chains.reserve(ends.size());
  for (const PlanEnd& e : ends) chains.push_back({e.right, e.left});
  if (is_simple_outline(chains, order)) return order;
  std::vector<Polyline2> sorted;
  sorted.reserve(order.size());
  for (const std::size_t k : order) sorted.push_back(chains[k]);
  const std::optional<std::vector<std::size_t>> simple = simple_outline_order(sorted);
  if (!simple) return order;
  std::vector<std::size_t> reordered;
  reordered.reserve(simple->size());
  for (const std::size_t k : *simple) reordered.push_back(order[k]);
  return reordered;
}

}  // namespace relief::detail
