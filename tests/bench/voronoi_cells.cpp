// Every Voronoi cell of n uniform random sites in the unit square (Google Benchmark):
// protocols::voronoi_cells, and, when CGAL is installed (Debian: libcgal-dev), the
// Delaunay-dual route on the same sites — CGAL::Delaunay_triangulation_2, then each cell as the
// domain clipped by the bisectors of the site's Delaunay neighbours. Results: docs/performance.md.
//   masnet_bench_voronoi_cells [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "protocols/geometry.hpp"
#include "sim/random.hpp"

#ifdef MASNET_BENCH_WITH_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <utility>
#endif

using namespace masnet;
using net::Vec2;

namespace {

std::vector<Vec2> uniform_sites(std::int64_t n) {
  sim::RandomStream rng(1);
  std::vector<Vec2> sites;
  for (std::int64_t i = 0; i < n; ++i)
    sites.push_back(Vec2{rng.uniform01(), rng.uniform01()});
  return sites;
}

void masnet_voronoi_cells(benchmark::State& state) {
  const std::vector<Vec2> sites = uniform_sites(state.range(0));
  const protocols::ConvexPolygon domain = protocols::rectangle(0, 0, 1, 1);
  std::size_t sink = 0;
  for (auto _ : state) {
    const std::vector<protocols::Cell> cells = protocols::voronoi_cells(sites, domain);
    sink += cells.back().polygon.vertices.size();
  }
  benchmark::DoNotOptimize(sink);
}
BENCHMARK(masnet_voronoi_cells)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

#ifdef MASNET_BENCH_WITH_CGAL
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using Delaunay = CGAL::Delaunay_triangulation_2<
    Kernel,
    CGAL::Triangulation_data_structure_2<VertexBase, CGAL::Triangulation_face_base_2<Kernel>>>;

// The same output as a protocols::Cell (polygon and sorted neighbour list), built from the
// Delaunay neighbours by plain Sutherland–Hodgman clipping of the domain.
struct PlainCell {
  std::vector<Vec2> polygon;
  std::vector<std::uint32_t> neighbours;
};

void clip_by_bisector(std::vector<Vec2>& poly, std::vector<Vec2>& scratch, const Vec2& p,
                      const Vec2& q) {
  const Vec2 normal = q - p;
  const double offset = 0.5 * normal.dot(q + p);
  scratch.clear();
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[i + 1 == n ? 0 : i + 1];
    const double sa = normal.dot(a) - offset, sb = normal.dot(b) - offset;
    if (sa <= 0.0) scratch.push_back(a);
    if ((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0))
      scratch.push_back(a + (sa / (sa - sb)) * (b - a));
  }
  poly.swap(scratch);
}

void cgal_delaunay_dual(benchmark::State& state) {
  const std::vector<Vec2> sites = uniform_sites(state.range(0));
  const protocols::ConvexPolygon domain = protocols::rectangle(0, 0, 1, 1);
  std::vector<std::pair<Kernel::Point_2, std::uint32_t>> points;
  for (std::size_t i = 0; i < sites.size(); ++i)
    points.emplace_back(Kernel::Point_2(sites[i].x(), sites[i].y()), static_cast<std::uint32_t>(i));
  std::size_t sink = 0;
  std::vector<Vec2> polygon, scratch;
  std::vector<std::uint32_t> neighbours;
  for (auto _ : state) {
    Delaunay dt(points.begin(), points.end());  // spatially sorted insertion
    std::vector<PlainCell> cells(sites.size());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
      const std::uint32_t i = v->info();
      PlainCell& cell = cells[i];
      polygon.assign(domain.vertices.begin(), domain.vertices.end());
      neighbours.clear();
      auto c = dt.incident_vertices(v), done = c;
      do {
        if (!dt.is_infinite(c)) {
          neighbours.push_back(c->info());
          clip_by_bisector(polygon, scratch, sites[i], sites[c->info()]);
        }
      } while (++c != done);
      std::sort(neighbours.begin(), neighbours.end());
      // One exact allocation each, as protocols::voronoi_cells makes.
      cell.polygon.assign(polygon.begin(), polygon.end());
      cell.neighbours.assign(neighbours.begin(), neighbours.end());
    }
    sink += cells.back().polygon.size();
  }
  benchmark::DoNotOptimize(sink);
}
BENCHMARK(cgal_delaunay_dual)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

// The triangulation alone: the part of the route above that is CGAL's.
void cgal_triangulation_only(benchmark::State& state) {
  const std::vector<Vec2> sites = uniform_sites(state.range(0));
  std::vector<std::pair<Kernel::Point_2, std::uint32_t>> points;
  for (std::size_t i = 0; i < sites.size(); ++i)
    points.emplace_back(Kernel::Point_2(sites[i].x(), sites[i].y()), static_cast<std::uint32_t>(i));
  std::size_t sink = 0;
  for (auto _ : state) {
    Delaunay dt(points.begin(), points.end());
    sink += dt.number_of_vertices();
  }
  benchmark::DoNotOptimize(sink);
}
BENCHMARK(cgal_triangulation_only)->Arg(10000)->Unit(benchmark::kMillisecond);
#endif

}  // namespace

BENCHMARK_MAIN();
