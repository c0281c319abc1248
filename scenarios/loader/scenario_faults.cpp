// Scripted faults (the top-level `faults` list) and the robots' locomotion energy
// (`robots.energy`): docs/scenario-reference.md, "faults"; the model is in
// docs/faults-and-lifetime.md.
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "protocols/geometry.hpp"
#include "scenarios/loader/scenario_parts.hpp"

namespace masnet::scenarios {
namespace {

using agents::FaultDef;
using agents::FaultKind;
using agents::FaultNodes;

// Reports a problem with the section itself (a key it lacks that has no place to point at).
void error_here(Section& s, const std::string& message) {
  s.reader().error(s.where(), s.path() + ": " + message);
}

// All vertices on one line (or one point): a polygon without area. Exact, like is_simple.
bool on_one_line(const std::vector<Vec2>& vertices) {
  const Vec2& a = vertices.front();
  const Vec2* b = nullptr;
  for (const Vec2& v : vertices) {
    if (v == a) continue;
    if (!b) {
      b = &v;
      continue;
    }
    const double cross = (b->x() - a.x()) * (v.y() - a.y()) - (b->y() - a.y()) * (v.x() - a.x());
    if (cross != 0.0) return false;
  }
  return true;
}

// A disk {center, radius} or a polygon {polygon: [[x, y], ...]} of at least 3 vertices, with
// an area and no self-intersection, in either orientation.
net::Region read_region(Section s) {
  net::Region region;
  const bool disk = s.has("center") || s.has("radius"), polygon = s.has("polygon");
  if (!disk && !polygon) {
    error_here(s, "a region needs 'center' and 'radius' (a disk) or 'polygon: [[x, y], ...]'");
    for (const char* key : {"center", "radius", "polygon"})
      s.mark_known(key);
  } else if (polygon && disk) {
    s.error_at("polygon", "give either 'center' and 'radius' (a disk) or 'polygon', not both");
    for (const char* key : {"center", "radius", "polygon"})
      s.mark_known(key);
  } else if (polygon) {
    region.shape = net::Region::Shape::polygon;
    const std::size_t errors_before = s.reader().diagnostics().size();
    region.polygon = s.points("polygon", 3);
    if (s.reader().diagnostics().size() == errors_before) {
      // A bow tie's signed areas cancel: only collinear vertices mean "no area".
      if (on_one_line(region.polygon))
        s.error_at("polygon", "the polygon has no area (its vertices lie on one line)");
      else if (!protocols::is_simple(region.polygon))
        s.error_at("polygon", "the polygon intersects itself");
    }
    s.mark_known("center");
    s.mark_known("radius");
  } else {
    region.shape = net::Region::Shape::disk;
    if (!s.has("center")) s.error_at("center", "a disk needs 'center: [x, y]'");
    region.center = s.point("center", Vec2{0, 0});
    if (!s.has("radius")) s.error_at("radius", "a disk needs 'radius' (world units, > 0)");
    region.radius = s.number("radius", 1.0, Range::positive());
    s.mark_known("polygon");
  }
  s.finish();
  return region;
}

// The nodes a kill takes: exactly one of `ids`, `fraction` and `region`.
void read_kill(Section& f, FaultDef& fault, const NodeCounts& counts) {
  fault.nodes =
      f.choice<FaultNodes>("kill", FaultNodes::robots,
                           {{"robots", FaultNodes::robots}, {"sensors", FaultNodes::sensors}});
  const bool robots = fault.nodes == FaultNodes::robots;
  const std::string what = robots ? "robot" : "sensor";
  const std::vector<const char*> choosers = {"ids", "fraction", "region"};
  const char* chosen = nullptr;
  for (const char* key : choosers)
    if (f.has(key)) {
      if (chosen)
        f.error_at(key, std::string("give one of 'ids', 'fraction' or 'region', not both '") +
                            chosen + "' and '" + key + "'");
      else
        chosen = key;
    }
  if (!chosen)
    f.error_at("kill", "a kill needs 'ids', 'fraction' or 'region' (which nodes it takes)");
  const std::string_view pick = chosen ? chosen : "";
  if (pick == "ids") {
    const std::optional<std::size_t> count = robots ? counts.robots : counts.sensors;
    if (count && *count == 0) {
      f.error_at("ids", "the scenario has no " + what + "s");
      f.mark_known("ids");
    } else {
      const std::int64_t last =
          count ? static_cast<std::int64_t>(*count) - 1 : std::numeric_limits<std::uint32_t>::max();
      const std::size_t errors_before = f.reader().diagnostics().size();
      for (const std::int64_t id : f.distinct_integers("ids", 0, last, what))
        fault.ids.push_back(static_cast<std::uint32_t>(id));
      if (fault.ids.empty() && f.reader().diagnostics().size() == errors_before)
        f.error_at("ids", "an empty list kills nobody; give at least one " + what);
    }
  } else {
    f.mark_known("ids");
  }
  if (pick == "fraction")
    fault.fraction = f.number("fraction", 0.0, Range::unit());
  else
    f.mark_known("fraction");
  if (pick == "region")
    fault.region = read_region(f.section("region"));
  else
    f.mark_known("region");
}

// A line no frame crosses.
void read_partition(Section p, FaultDef& fault) {
  if (!p.has("line")) p.error_at("line", "a partition needs 'line: [[x1, y1], [x2, y2]]'");
  const std::size_t errors_before = p.reader().diagnostics().size();
  const std::vector<Vec2> ends = p.points("line");
  if (p.has("line") && p.reader().diagnostics().size() == errors_before) {
    if (ends.size() != 2)
      p.error_at("line", "expected the two ends of a segment [[x1, y1], [x2, y2]] (got " +
                             std::to_string(ends.size()) + " points)");
    else if (ends[0] == ends[1])
      p.error_at("line", "the two ends are the same point " + shown_point(ends[0]));
  }
  if (ends.size() == 2) fault.line = net::LineCut{ends[0], ends[1]};
  p.finish();
}

// Extra loss in a region.
void read_degrade(Section d, FaultDef& fault) {
  if (!d.has("loss"))
    d.error_at("loss", "missing required key 'loss' (the probability that a reception is lost)");
  fault.loss = d.number("loss", 0.0, Range::unit());
  if (d.has("region")) {
    fault.region = read_region(d.section("region"));
  } else {
    d.error_at("region", "a degraded area needs 'region' (a disk or a polygon)");
    d.mark_known("region");
  }
  d.finish();
}

FaultDef read_fault(Section& f, double end_s, const NodeCounts& counts) {
  FaultDef fault;
  if (!f.has("at")) f.error_at("at", "missing required key 'at' (when the fault strikes, s)");
  fault.at_s = f.number("at", 0.0, Range{0.0, end_s, false, true});
  // Absent: for good; the resolved scenario then has no `until` either.
  if (f.has("until")) {
    fault.until_s = f.number("until", end_s, Range{0.0, end_s});
    if (fault.until_s <= fault.at_s) {
      std::ostringstream text;
      text << "must be > at = " << fault.at_s << " (got " << fault.until_s << ")";
      f.error_at("until", text.str());
    }
  } else {
    f.mark_known("until");
  }
  const char* kinds[] = {"kill", "partition", "degrade"};
  const char* kind = nullptr;
  for (const char* key : kinds)
    if (f.has(key)) {
      if (kind)
        f.error_at(key, std::string("give one of 'kill', 'partition' or 'degrade' per fault, "
                                    "not both '") +
                            kind + "' and '" + key + "'");
      else
        kind = key;
    }
  if (!kind)
    error_here(f, "a fault needs one of 'kill', 'partition' or 'degrade' (what goes wrong)");
  const std::string_view k = kind ? kind : "";
  if (k == "kill") {
    fault.kind = FaultKind::kill;
    read_kill(f, fault, counts);
  } else {
    f.mark_known("kill");
    for (const char* key : {"ids", "fraction", "region"})
      if (kind)
        f.reject(key, std::string("'") + key + "' applies to a kill" +
                          (std::string_view(key) == "region" && k == "degrade"
                               ? " (a degraded area's region goes inside 'degrade')"
                               : ""));
      else
        f.mark_known(key);
  }
  if (k == "partition") {
    fault.kind = FaultKind::partition;
    read_partition(f.section("partition"), fault);
  } else {
    f.mark_known("partition");
  }
  if (k == "degrade") {
    fault.kind = FaultKind::degrade;
    read_degrade(f.section("degrade"), fault);
  } else {
    f.mark_known("degrade");
  }
  f.finish();
  return fault;
}

}  // namespace

agents::LocomotionEnergy read_locomotion(Section s) {
  agents::LocomotionEnergy e;
  e.per_metre_j = s.number("per_metre", e.per_metre_j, Range::non_negative());
  e.per_accel_j = s.number("per_accel", e.per_accel_j, Range::non_negative());
  s.finish();
  return e;
}

std::vector<FaultDef> read_faults(Section& top, double duration_s, const NodeCounts& counts) {
  std::vector<FaultDef> faults;
  // No list: nothing in the resolved scenario (like `limits`).
  if (!top.has("faults")) {
    top.mark_known("faults");
    return faults;
  }
  const double end_s = duration_s > 0.0 ? duration_s : kMaxTime_s;
  for (Section f : top.sections("faults"))
    faults.push_back(read_fault(f, end_s, counts));
  return faults;
}

}  // namespace masnet::scenarios
