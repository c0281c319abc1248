#pragma once
// The builder of one bounded Voronoi cell, used by voronoi_cell (geometry.cpp) and
// voronoi_cells (voronoi_cells.cpp); internal to the protocols library, not part of its API.
// Tolerances and degenerate cases: docs/geometry.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>  // baseline x86-64
#endif

#include "protocols/geometry.hpp"
#include "protocols/geometry_internal.hpp"

namespace masnet::protocols::geometry_internal {

// Edge labels of a cell under construction; candidate indices use the rest of the range.
inline constexpr std::uint32_t kDomainLabel = 0xFFFFFFFFu;
inline constexpr std::uint32_t kDiskLabel = 0xFFFFFFFEu;

/// Removes, until none is left, vertices closer than tol_len to their successor and vertices
/// whose turn is not strictly left (exact). labels[i] names edge i → i+1; a merged edge keeps
/// the label of its longer part. Fewer than 3 vertices left: the polygon is empty.
void canonicalize(std::vector<Vec2>& pts, std::vector<std::uint32_t>& labels, double tol_len);

/// bisector_half_plane, inline for the cell builders' inner loop (geometry.cpp's definition
/// calls this one, so both always agree).
inline HalfPlane bisector(const Vec2& site, const Vec2& other) {
  // |q − site|² <= |q − other|²  ⟺  (other − site)·q <= (|other|² − |site|²) / 2.
  const Vec2 normal = other - site;
  return HalfPlane{normal, 0.5 * normal.dot(other + site)};
}

/// canonicalize() on the first n entries of two arrays; n becomes the count left.
void canonicalize(Vec2* pts, std::uint32_t* labels, std::size_t& n, double tol_len);

/// A convex polygon whose edges carry the label of the constraint that made them, clipped in
/// place by ping-ponging between two buffers (no allocation once the buffers have grown).
class LabelledClipper {
 public:
  void reset(std::span<const Vec2> vertices, std::uint32_t label) {
    n_ = vertices.size();
    reserve(n_);
    std::copy(vertices.begin(), vertices.end(), pts_.begin());
    std::fill_n(labels_.begin(), n_, label);
    canonical_tol_ = -1.0;
  }
  bool empty() const { return n_ == 0; }
  std::span<const Vec2> points() const { return {pts_.data(), n_}; }
  std::span<const std::uint32_t> labels() const { return {labels_.data(), n_}; }
  void clear() { n_ = 0; }

  template <class Predicate>
  void relabel_if(Predicate&& predicate, std::uint32_t label) {
    for (std::size_t i = 0; i < n_; ++i)
      if (predicate(labels_[i])) labels_[i] = label;
  }

  double max_distance_sq(const Vec2& p) const {
    // Four vertices at a time, the padding entries counted as 0 (see clip()).
    double d2 = 0.0;
    for (std::size_t i = 0; i < n_; i += 4) {
      for (std::size_t j = i; j < i + 4; ++j)
        d2 = std::max(d2, j < n_ ? (pts_[j] - p).squaredNorm() : 0.0);
    }
    return d2;
  }

  /// Clips by `hp`, giving new edges `label`. `scale` is the coordinate magnitude setting the
  /// tolerances (kGeometryRelTol). Returns true when the polygon changed.
  /// Inline: most clips of a cell change nothing, and this much decides it.
  bool clip(const HalfPlane& hp, std::uint32_t label, double scale) {
    const std::size_t n = n_;
    if (n == 0) return false;
    const double nx = hp.normal.x(), ny = hp.normal.y(), offset = hp.offset;
    // Rounding error of nx·x + ny·y − offset is a few ulps of this magnitude.
    const double tol = kGeometryRelTol * ((std::abs(nx) + std::abs(ny)) * scale + std::abs(offset));
    const Vec2* pts = pts_.data();
    double* side = side_.data();
    // Bit i set: vertex i strictly out (out_mask), strictly in (in_mask).
    std::uint64_t out_mask = 0, in_mask = 0;
    // Vertex j's signed distance and bits (bit j mod 64: past 64 vertices only "any" counts).
    auto mark = [&](std::size_t j) {
      const double s = nx * pts[j].x() + ny * pts[j].y() - offset;
      side[j] = s;
      out_mask |= std::uint64_t{s > tol} << (j & 63);
      in_mask |= std::uint64_t{s < -tol} << (j & 63);
    };
    if (n <= 60) {
      // Four vertices at a time: a loop of random length would mispredict its end. The
      // entries past n are padding (reserve), their bits dropped.
#if defined(__SSE2__)
      // Two vertices per register, each side rounded as mark() rounds it.
      const __m128d nxs = _mm_set1_pd(nx), nys = _mm_set1_pd(ny), offsets = _mm_set1_pd(offset);
      const __m128d tols = _mm_set1_pd(tol), minus_tols = _mm_set1_pd(-tol);
      for (std::size_t i = 0; i < n; i += 4) {
        for (std::size_t j = i; j < i + 4; j += 2) {
          const __m128d a = _mm_loadu_pd(pts[j].data()), b = _mm_loadu_pd(pts[j + 1].data());
          const __m128d xs = _mm_unpacklo_pd(a, b), ys = _mm_unpackhi_pd(a, b);
          const __m128d s =
              _mm_sub_pd(_mm_add_pd(_mm_mul_pd(nxs, xs), _mm_mul_pd(nys, ys)), offsets);
          _mm_storeu_pd(side + j, s);
          out_mask |= std::uint64_t(_mm_movemask_pd(_mm_cmpgt_pd(s, tols))) << j;
          in_mask |= std::uint64_t(_mm_movemask_pd(_mm_cmplt_pd(s, minus_tols))) << j;
        }
      }
#else
      for (std::size_t i = 0; i < n; i += 4)
        for (std::size_t j = i; j < i + 4; ++j)
          mark(j);
#endif
      const std::uint64_t all = (std::uint64_t{1} << n) - 1;
      out_mask &= all;
      in_mask &= all;
    } else {
      for (std::size_t j = 0; j < n; ++j)
        mark(j);
    }
    if (out_mask == 0) return false;
    if (in_mask == 0) {  // at most a tol-thin sliver would remain
      clear();
      return true;
    }
    cut(label, tol, scale, out_mask, in_mask);
    return true;
  }

 private:
  static constexpr std::uint32_t kNewVertex = 0xFFFFFFFFu;
  // The Sutherland–Hodgman pass of clip() once side_ holds every vertex's signed distance and
  // some vertex is strictly in, some strictly out.
  void cut(std::uint32_t label, double tol, double scale, std::uint64_t out_mask,
           std::uint64_t in_mask);
  // Makes the m vertices of the next buffers the polygon, canonicalised unless `canonical`.
  void adopt_cut(std::size_t m, bool canonical, double tol_len);
  // cut() for the usual case: no vertex on the line, one run of vertices out. Returns the
  // output vertex count, written to next_pts_ and next_labels_ exactly as the general pass
  // would; its three seams are consecutive, from first_seam on.
  std::size_t cut_one_run(std::uint32_t label, std::uint64_t out_mask, std::uint64_t in_mask,
                          std::size_t& first_seam);
  // Room for `count` vertices in every buffer: the clip output gets twice that, and
  // kPadding more for the passes that work four vertices at a time.
  static constexpr std::size_t kPadding = 4;
  void reserve(std::size_t count) {
    const std::size_t size = 2 * count + kPadding;
    if (pts_.size() >= size) return;
    for (std::vector<Vec2>* v : {&pts_, &next_pts_})
      v->resize(size, Vec2::Zero());  // the padding is read: never indeterminate
    for (std::vector<std::uint32_t>* v : {&labels_, &next_labels_})
      v->resize(size);
    side_.resize(size);
  }
  // Most edges a clip leaves between vertices consecutive before it; the others are seams.
  static constexpr std::size_t kMaxSeams = 8;
  // True when canonicalize() would change nothing in the m vertices of next_pts_: they were
  // canonical with tol_len before the clip, so only the edges listed in seams (by their first
  // vertex) and the turns at their ends can fail its tests.
  bool seams_pass(std::size_t m, std::span<const std::size_t> seams, double tol_len) const;
  // seams_pass() for the three consecutive seams of a one-run cut, the first at vertex a,
  // every test made (no early exit to mispredict).
  bool run_seams_pass(std::size_t m, std::size_t a, double tol_len) const;

  // Buffers sized once to at least twice the vertex count; the polygon is the first n_.
  std::vector<Vec2> pts_, next_pts_;
  std::vector<std::uint32_t> labels_, next_labels_;
  std::vector<double> side_;
  std::size_t n_ = 0;
  // The tolerance the current vertices were last made canonical with; < 0 when unknown.
  double canonical_tol_ = -1.0;
};

/// One cell under construction: the site, the tolerance scale and the farthest vertex, which
/// decides which candidates can still cut the cell.
class CellBuilder {
 public:
  /// `sites` (viewed, not copied) resolves coincident candidates. `sites_may_coincide` false
  /// promises that no two sites are equal, which makes the relabelling of a repeated bisector
  /// (add_candidate) a no-op that is skipped.
  void start(std::uint32_t site, std::span<const Vec2> sites, const ConvexPolygon& domain,
             bool sites_may_coincide = true) {
    site_ = site;
    sites_ = sites;
    sites_may_coincide_ = sites_may_coincide;
    p_ = sites[site];
    scale_ =
        std::max(max_abs_coordinate(domain.vertices), std::max(std::abs(p_.x()), std::abs(p_.y())));
    clipper_.reset(domain.vertices, kDomainLabel);
    reach_sq_ = clipper_.max_distance_sq(p_);
    clips_ = 0;
  }
  bool empty() const { return clipper_.empty(); }
  double reach_sq() const { return reach_sq_; }

  /// Applies candidate c at q. Returns false once the cell is empty (nothing left to do).
  bool add_candidate(std::uint32_t c, const Vec2& q) {
    if (c == site_ || clipper_.empty()) return !clipper_.empty();
    if (q.x() == p_.x() && q.y() == p_.y()) {  // coincident: the lower index keeps the cell
      if (c < site_) clipper_.clear();
      return !clipper_.empty();
    }
    // The bisector lies |q − p|/2 from p; beyond the farthest vertex it cannot cut.
    if ((q - p_).squaredNorm() > 4.0 * reach_sq_) return true;
    ++clips_;
    if (clipper_.clip(bisector(p_, q), c, scale_)) {
      reach_sq_ = clipper_.max_distance_sq(p_);
    } else if (sites_may_coincide_) {
      // The same bisector may already bound the cell under a coincident copy of q; the
      // lower index names it, since the higher one's cell is empty.
      clipper_.relabel_if(
          [&](std::uint32_t label) {
            return label > c && label < sites_.size() && sites_[label] == q;
          },
          c);
    }
    return !clipper_.empty();
  }

  /// Intersects with the kDiskSides-gon circumscribing B(p, radius); skipped when every vertex
  /// is already within the inscribed disk.
  void add_disk(double radius);

  Cell finish() const;

 private:
  LabelledClipper clipper_;
  std::uint32_t site_ = 0;
  std::span<const Vec2> sites_;
  bool sites_may_coincide_ = true;
  Vec2 p_ = Vec2::Zero();
  double scale_ = 0.0, reach_sq_ = 0.0;
  std::uint32_t clips_ = 0;  // since start(): the cell's computation-load count
};

}  // namespace masnet::protocols::geometry_internal
