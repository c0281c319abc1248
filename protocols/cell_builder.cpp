#include "protocols/cell_builder.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>

namespace masnet::protocols::geometry_internal {
namespace {

// orientation(), with its floating-point filter inline: most turns are decided here, the rest
// by orientation()'s exact expansion. The same answer as orientation() always.
int turn(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (b.x() - a.x()) * (c.y() - a.y());
  const double right = (b.y() - a.y()) * (c.x() - a.x());
  const double det = left - right;
  const double bound = 3.3306690738754716e-16 * (std::abs(left) + std::abs(right));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orientation(a, b, c);
}

// Unit outward normals of the disk polygon's edges, at angles 2πk/kDiskSides.
const std::array<Vec2, kDiskSides>& disk_normals() {
  static const std::array<Vec2, kDiskSides> normals = [] {
    std::array<Vec2, kDiskSides> u;
    for (int k = 0; k < kDiskSides; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / kDiskSides;
      u[static_cast<std::size_t>(k)] = Vec2{std::cos(angle), std::sin(angle)};
    }
    return u;
  }();
  return normals;
}

// Crossing of edge i → j (one side strictly in, the other strictly out), interpolated from
// the inside vertex so both orders of the same edge give the same point.
Vec2 crossing(const Vec2* pts, const double* side, std::size_t i, std::size_t j) {
  const std::size_t in = side[i] < 0.0 ? i : j, out = in == i ? j : i;
  const double t = side[in] / (side[in] - side[out]);
  return pts[in] + t * (pts[out] - pts[in]);
}

}  // namespace

void canonicalize(Vec2* pts, std::uint32_t* labels, std::size_t& n, double tol_len) {
  const double tol_sq = tol_len * tol_len;
  // Removes entry k of both arrays.
  auto erase = [&](std::size_t k) {
    std::copy(pts + k + 1, pts + n, pts + k);
    std::copy(labels + k + 1, labels + n, labels + k);
    --n;
  };
  bool changed = true;
  while (changed && n >= 3) {
    changed = false;
    for (std::size_t i = 0; i < n && n >= 3;) {
      const std::size_t prev = i == 0 ? n - 1 : i - 1, next = i + 1 == n ? 0 : i + 1;
      if ((pts[next] - pts[i]).squaredNorm() <= tol_sq) {
        labels[i] = labels[next];
        erase(next);
        changed = true;
        continue;
      }
      if (turn(pts[prev], pts[i], pts[next]) <= 0) {
        if ((pts[next] - pts[i]).squaredNorm() > (pts[i] - pts[prev]).squaredNorm())
          labels[prev] = labels[i];
        erase(i);
        changed = true;
        continue;
      }
      ++i;
    }
  }
  if (n < 3) n = 0;
}

void canonicalize(std::vector<Vec2>& pts, std::vector<std::uint32_t>& labels, double tol_len) {
  std::size_t n = pts.size();
  canonicalize(pts.data(), labels.data(), n, tol_len);
  pts.resize(n);
  labels.resize(n);
}

std::size_t LabelledClipper::cut_one_run(std::uint32_t label, std::uint64_t out_mask,
                                         std::uint64_t in_mask, std::size_t& first_seam) {
  const std::size_t n = n_;
  const Vec2* pts = pts_.data();
  const std::uint32_t* labels = labels_.data();
  Vec2* out_pts = next_pts_.data();
  std::uint32_t* out_labels = next_labels_.data();
  // The run out is first_out..last_out (cyclically); the vertex before it leaves, the one
  // after it enters. The general pass starts at vertex 0, so where it lies sets the order.
  // Copies vertices first..last four at a time (a copy of random length would mispredict its
  // end); the buffers' padding (reserve) holds the few extra entries, overwritten or ignored.
  auto copy_in = [&](std::size_t first, std::size_t last, std::size_t to) {
    for (std::size_t k = 0; k <= last - first; k += 4) {
      for (std::size_t j = 0; j < 4; ++j) {
        out_pts[to + k + j] = pts[first + k + j];
        out_labels[to + k + j] = labels[first + k + j];
      }
    }
  };
  if (in_mask & 1u) {  // vertices 0..first_out−1, X1, X2, last_out+1..n−1
    const auto first_out = static_cast<std::size_t>(std::countr_zero(out_mask));
    const auto last_out = static_cast<std::size_t>(63 - std::countl_zero(out_mask));
    copy_in(0, first_out - 1, 0);
    std::size_t m = first_out;
    out_pts[m] = crossing(pts, side_.data(), first_out - 1, first_out);
    out_labels[m++] = label;
    out_pts[m] = crossing(pts, side_.data(), last_out, last_out + 1 == n ? 0 : last_out + 1);
    out_labels[m++] = labels[last_out];
    if (last_out + 1 < n) {
      copy_in(last_out + 1, n - 1, m);
      m += n - 1 - last_out;
    }
    first_seam = first_out - 1;
    return m;
  }
  // Vertex 0 out: X2, vertices last_out+1..first_out−1 (the run in), X1.
  const auto first_in = static_cast<std::size_t>(std::countr_zero(in_mask));
  const auto last_in = static_cast<std::size_t>(63 - std::countl_zero(in_mask));
  out_pts[0] = crossing(pts, side_.data(), first_in - 1, first_in);
  out_labels[0] = labels[first_in - 1];
  copy_in(first_in, last_in, 1);
  const std::size_t count_in = last_in - first_in + 1;
  out_pts[count_in + 1] = crossing(pts, side_.data(), last_in, last_in + 1 == n ? 0 : last_in + 1);
  out_labels[count_in + 1] = label;
  first_seam = count_in;  // seams count_in, count_in + 1 and 0: the last edges and the first
  return count_in + 2;
}

void LabelledClipper::cut(std::uint32_t label, double tol, double scale, std::uint64_t out_mask,
                          std::uint64_t in_mask) {
  const double tol_len = kGeometryRelTol * scale;
  const std::size_t n = n_;
  if (n >= 3 && n <= 64) {
    const std::uint64_t all = n == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1;
    // One run out: exactly two places where out and in alternate around the polygon.
    const std::uint64_t shifted = ((out_mask >> 1) | (out_mask << (n - 1))) & all;
    const std::uint64_t changes = out_mask ^ shifted;
    const std::uint64_t after_lowest = changes & (changes - 1);
    // (Two bits set, tested without std::popcount: this target has no instruction for it.)
    if ((out_mask | in_mask) == all && after_lowest != 0 &&
        (after_lowest & (after_lowest - 1)) == 0) {
      std::size_t first_seam = 0;
      const std::size_t m = cut_one_run(label, out_mask, in_mask, first_seam);
      adopt_cut(m, canonical_tol_ == tol_len && m >= 3 && run_seams_pass(m, first_seam, tol_len),
                tol_len);
      return;
    }
  }
  const Vec2* pts = pts_.data();
  const std::uint32_t* labels = labels_.data();
  const double* side = side_.data();
  // Each vertex emits at most two, and the buffers hold twice the vertex count.
  Vec2* out_pts = next_pts_.data();
  std::uint32_t* out_labels = next_labels_.data();
  std::size_t m = 0;
  // Edges between vertices that were not consecutive before (by first vertex): at most a few
  // for a convex cut; past kMaxSeams the full canonicalize() decides.
  std::array<std::size_t, kMaxSeams> seams;
  std::size_t seam_count = 0;
  bool too_many_seams = false;
  std::size_t last_origin = kNewVertex;
  auto push = [&](const Vec2& p, std::uint32_t l, std::size_t from) {
    if (m > 0 && !(from != kNewVertex && last_origin != kNewVertex && from == last_origin + 1)) {
      if (seam_count < kMaxSeams) {
        seams[seam_count++] = m - 1;
      } else {
        too_many_seams = true;
      }
    }
    last_origin = from;
    out_pts[m] = p;
    out_labels[m] = l;
    ++m;
  };
  auto intersection = [&](std::size_t i, std::size_t j) { return crossing(pts, side, i, j); };
  std::size_t first_origin = kNewVertex;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i + 1 == n ? 0 : i + 1;
    const double si = side[i], sj = side[j];
    if (si <= tol) {
      if (m == 0) first_origin = i;
      if (sj <= tol) {
        push(pts[i], labels[i], i);
      } else if (si < -tol) {  // leaving: the edge now ends on the line, which follows
        push(pts[i], labels[i], i);
        push(intersection(i, j), label, kNewVertex);
      } else {  // on the line, next vertex outside: the line follows directly
        push(pts[i], label, i);
      }
    } else if (sj < -tol) {  // entering: the rest of edge i stays
      push(intersection(i, j), labels[i], kNewVertex);
    }
  }
  // The closing edge, last vertex to first.
  if (m > 0 && !(last_origin == n - 1 && first_origin == 0)) {
    if (seam_count < kMaxSeams) {
      seams[seam_count++] = m - 1;
    } else {
      too_many_seams = true;
    }
  }
  // canonicalize() changes nothing when every turn passes; those between vertices that were
  // consecutive before already passed with this tolerance, so only the seams are tested.
  adopt_cut(m,
            canonical_tol_ == tol_len && m >= 3 && !too_many_seams &&
                seams_pass(m, std::span<const std::size_t>(seams.data(), seam_count), tol_len),
            tol_len);
}

void LabelledClipper::adopt_cut(std::size_t m, bool canonical, double tol_len) {
  pts_.swap(next_pts_);
  labels_.swap(next_labels_);
  n_ = m;
  if (!canonical) canonicalize(pts_.data(), labels_.data(), n_, tol_len);
  reserve(n_);
  canonical_tol_ = tol_len;
}

bool LabelledClipper::seams_pass(std::size_t m, std::span<const std::size_t> seams,
                                 double tol_len) const {
  const double tol_sq = tol_len * tol_len;
  const Vec2* pts = next_pts_.data();
  auto next = [m](std::size_t k) { return k + 1 == m ? 0 : k + 1; };
  auto prev = [m](std::size_t k) { return k == 0 ? m - 1 : k - 1; };
  // Seams come in increasing order and a cut's are usually consecutive: the turn at a seam's
  // end is then the next seam's first, tested once.
  std::size_t turn_tested = m;
  for (std::size_t a : seams) {
    const std::size_t b = next(a);
    if ((pts[b] - pts[a]).squaredNorm() <= tol_sq) return false;
    if (a != turn_tested && turn(pts[prev(a)], pts[a], pts[b]) <= 0) return false;
    if (turn(pts[a], pts[b], pts[next(b)]) <= 0) return false;
    turn_tested = b;
  }
  return true;
}

bool LabelledClipper::run_seams_pass(std::size_t m, std::size_t a, double tol_len) const {
  const double tol_sq = tol_len * tol_len;
  const Vec2* pts = next_pts_.data();
  // Vertices a − 1 … a + 4 around the polygon.
  std::array<std::size_t, 6> v;
  std::size_t k = a == 0 ? m - 1 : a - 1;
  for (std::size_t& index : v) {
    index = k;
    k = k + 1 == m ? 0 : k + 1;
  }
  bool pass = true;
  for (std::size_t e = 1; e <= 3; ++e)  // the seams' lengths: edges a → a+1 … a+2 → a+3
    pass &= (pts[v[e + 1]] - pts[v[e]]).squaredNorm() > tol_sq;
  for (std::size_t t = 1; t <= 4; ++t)  // the turns at a … a+3
    pass &= turn(pts[v[t - 1]], pts[v[t]], pts[v[t + 1]]) > 0;
  return pass;
}

void CellBuilder::add_disk(double radius) {
  if (clipper_.empty() || !(radius < kNoDisk) || reach_sq_ <= radius * radius) return;
  for (const Vec2& u : disk_normals()) {
    ++clips_;
    clipper_.clip(HalfPlane{u, u.dot(p_) + radius}, kDiskLabel, scale_);
    if (clipper_.empty()) break;
  }
  reach_sq_ = clipper_.max_distance_sq(p_);
}

Cell CellBuilder::finish() const {
  Cell cell;
  cell.polygon.vertices.assign(clipper_.points().begin(), clipper_.points().end());
  cell.half_plane_clips = clips_;
  cell.neighbours.reserve(clipper_.labels().size());
  for (std::uint32_t label : clipper_.labels()) {
    if (label == kDiskLabel) {
      cell.truncated = true;
    } else if (label != kDomainLabel) {
      cell.neighbours.push_back(label);
    }
  }
  std::vector<std::uint32_t>& nb = cell.neighbours;
  // Insertion sort past that (sorted input passes straight through).
  for (std::size_t i = 1; i < nb.size(); ++i) {
    const std::uint32_t v = nb[i];
    std::size_t k = i;
    for (; k > 0 && nb[k - 1] > v; --k)
      nb[k] = nb[k - 1];
    nb[k] = v;
  }
  cell.neighbours.erase(std::unique(cell.neighbours.begin(), cell.neighbours.end()),
                        cell.neighbours.end());
  return cell;
}

}  // namespace masnet::protocols::geometry_internal
