// write_paraview_state: the ParaView server-manager state of a few views of .pvd series. The
// proxies and properties are those ParaView 5.10/5.11 write (Remoting/*/Resources/*.xml of
// ParaView): only the properties that differ from their defaults are given; the loader keeps
// the defaults for the rest.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "sphark/io/atomic_file.hpp"
#include "sphark/io/paraview_state.hpp"
#include "sphark/io/vtk_series.hpp"  // xml_escape
#include "sphark/io/vtp_reader.hpp"

namespace sphark {

namespace fs = std::filesystem;

namespace {

struct Interval {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

struct Series {
  std::vector<std::pair<Real, std::string>> frames;
  Interval box[3];                      // bounds of the positions over every frame
  std::size_t particles = 0;            // of the first frame
  std::map<std::string, std::vector<double>> samples;  // values (vectors: magnitudes) of every frame
  std::map<std::string, int> components;
};

constexpr std::size_t kSamplesPerFrame = 20000;

Series scan_series(const fs::path& dir, const fs::path& pvd, const std::vector<std::string>& arrays) {
  Series s;
  s.frames = read_pvd(dir / pvd);
  if (s.frames.empty()) throw std::runtime_error("write_paraview_state: '" + (dir / pvd).string() + "' has no frames");
  for (const auto& [t, file] : s.frames) {
    const fs::path path = dir / pvd.parent_path() / file;
    const VtpContents f = read_frame(path);  // .vtp, or a distributed run's .pvtp
    if (s.particles == 0) s.particles = f.count;
    for (std::size_t i = 0; i < f.count; ++i)
      for (int c = 0; c < 3; ++c) s.box[c].add(f.points[3 * i + c]);
    for (const std::string& name : arrays) {
      const VtpArray* a = f.find(name);
      if (!a) throw std::runtime_error("write_paraview_state: '" + path.string() + "' has no point array '" + name + "'");
      std::vector<double>& r = s.samples[name];
      s.components[name] = a->components;
      const std::size_t stride = std::max<std::size_t>(1, f.count / kSamplesPerFrame);  // (a sample of big frames)
      for (std::size_t i = 0; i < f.count; i += stride) {
        double sq = 0;
        for (int c = 0; c < a->components; ++c) sq += a->values[i * a->components + c] * a->values[i * a->components + c];
        const double v = a->components == 1 ? a->values[i] : std::sqrt(sq);
        if (std::isfinite(v)) r.push_back(v);
      }
    }
  }
  return s;
}

std::string num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}


class StateXml {
 public:
  void open(const char* group, const char* type, int id, int servers) {
    id_ = std::to_string(id);
    x_ += "    <Proxy group=\"" + std::string(group) + "\" type=\"" + type + "\" id=\"" + id_ + "\" servers=\"" +
          std::to_string(servers) + "\">\n";
  }
  void close() { x_ += "    </Proxy>\n"; }
  void values(const std::string& name, const std::vector<std::string>& v) {
    head(name, v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      x_ += "        <Element index=\"" + std::to_string(i) + "\" value=\"" + xml_escape(v[i]) + "\"/>\n";
    x_ += "      </Property>\n";
  }
  void value(const std::string& name, const std::string& v) { values(name, {v}); }
  void numbers(const std::string& name, const std::vector<double>& v) {
    std::vector<std::string> t;
    for (double d : v) t.push_back(num(d));
    values(name, t);
  }
  void proxies(const std::string& name, const std::vector<int>& ids, bool input = false) {
    head(name, ids.size());
    for (int i : ids) x_ += "        <Proxy value=\"" + std::to_string(i) + (input ? "\" output_port=\"0\"/>\n" : "\"/>\n");
    x_ += "      </Property>\n";
  }
  void raw(const std::string& text) { x_ += text; }
  void collection(const std::string& name, const std::vector<std::pair<int, std::string>>& items) {
    x_ += "    <ProxyCollection name=\"" + name + "\">\n";
    for (const auto& [id, n] : items) x_ += "      <Item id=\"" + std::to_string(id) + "\" name=\"" + xml_escape(n) + "\"/>\n";
    x_ += "    </ProxyCollection>\n";
  }
  const std::string& text() const { return x_; }

 private:
  void head(const std::string& name, std::size_t n) {
    x_ += "      <Property name=\"" + name + "\" id=\"" + id_ + "." + name + "\" number_of_elements=\"" +
          std::to_string(n) + "\">\n";
  }
  std::string x_, id_;
};

constexpr int kTimeKeeper = 256, kScene = 257, kCue = 258, kLayout = 259;
int reader_id(std::size_t k) { return 1000 + static_cast<int>(k); }
int lut_id(std::size_t k) { return 2000 + static_cast<int>(k); }
int representation_id(std::size_t v) { return 3000 + static_cast<int>(v); }
int scalar_bar_id(std::size_t v) { return 4000 + static_cast<int>(v); }
int view_id(std::size_t v) { return 5000 + static_cast<int>(v); }

// The colour range of values: the central 99 % (0.5 % saturate at either end, so that a few
// outliers do not wash out the rest), symmetric about 0 for signed data (99 % of |v| inside);
// the full range where the central one is a single value.
Interval colour_range(std::vector<double> v) {
  Interval r;
  if (v.empty()) return r;
  const auto quantile = [&v](double q) {
    auto at = v.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), at, v.end());
    return *at;
  };
  for (double x : v) r.add(x);
  if (r.lo < 0 && r.hi > 0) {
    for (double& x : v) x = std::abs(x);
    const double m = quantile(0.99);
    if (m > 0) r = {-m, m};
  } else {
    const Interval central{quantile(0.005), quantile(0.995)};
    if (central.hi > central.lo) r = central;
  }
  return r;
}

// ParaView's default "Cool to Warm" map over [r.lo, r.hi].
void write_lut(StateXml& x, int id, Interval r) {
  if (!(r.hi > r.lo)) {  // constant (or empty): a unit window around the value
    const double c = std::isfinite(r.lo) ? r.lo : 0;
    r = {c - 1, c + 1};
  }
  const double mid = 0.5 * (r.lo + r.hi);
  x.open("lookup_tables", "PVLookupTable", id, 21);
  x.numbers("RGBPoints", {r.lo, 0.231373, 0.298039, 0.752941, mid, 0.865003, 0.865003, 0.865003, r.hi, 0.705882,
                          0.0156863, 0.14902});
  x.value("ColorSpace", "3");  // Diverging
  x.value("ScalarRangeInitialized", "1");
  x.value("AutomaticRescaleRangeMode", "0");  // grow and update on Apply (ParaView's default)
  x.value("VectorMode", "0");                 // vectors by magnitude
  x.close();
}

// A render view on the union of the series' bounds: 2D (every z = 0) from +z with a parallel
// projection, 3D in perspective from +z at 2 diagonals.
void write_view(StateXml& x, std::size_t v, const Series& s, std::size_t views) {
  const double c[3] = {0.5 * (s.box[0].lo + s.box[0].hi), 0.5 * (s.box[1].lo + s.box[1].hi),
                       0.5 * (s.box[2].lo + s.box[2].hi)};
  const double dx = s.box[0].hi - s.box[0].lo, dy = s.box[1].hi - s.box[1].lo, dz = s.box[2].hi - s.box[2].lo;
  const bool planar = dz == 0;
  const double extent = std::max({dx, dy, dz, 1e-300});
  x.open("views", "RenderView", static_cast<int>(view_id(v)), 21);
  x.proxies("Representations", {representation_id(v), scalar_bar_id(v)});
  x.numbers("CameraFocalPoint", {c[0], c[1], c[2]});
  x.numbers("CameraPosition", {c[0], c[1], c[2] + (planar ? extent : 2 * std::sqrt(dx * dx + dy * dy + dz * dz))});
  x.numbers("CameraViewUp", {0, 1, 0});
  x.numbers("CameraParallelScale", {(views > 1 ? 0.65 : 0.55) * std::max(dx, dy)});
  x.value("CameraParallelProjection", planar ? "1" : "0");
  x.numbers("CenterOfRotation", {c[0], c[1], c[2]});
  x.value("OrientationAxesVisibility", planar ? "0" : "1");
  x.close();
}

void write_representation(StateXml& x, std::size_t v, int reader, int lut, const ParaViewView& view, const Series& s) {
  const double dx = s.box[0].hi - s.box[0].lo, dy = s.box[1].hi - s.box[1].lo, dz = s.box[2].hi - s.box[2].lo;
  const double n = static_cast<double>(std::max<std::size_t>(s.particles, 1));
  const double spacing = dz > 0 ? std::cbrt(dx * dy * dz / n) : dy > 0 ? std::sqrt(dx * dy / n) : dx / n;
  x.open("representations", "GeometryRepresentation", representation_id(v), 21);
  x.proxies("Input", {reader}, true);
  x.value("Representation", "Point Gaussian");
  x.value("ShaderPreset", "3");  // plain circle
  x.numbers("GaussianRadius", {0.45 * spacing});  // (the bounding box's spacing: a little above the true one)
  x.values("ColorArrayName", {"", "", "", "0", view.array});  // 0: point data
  x.proxies("LookupTable", {lut});
  x.value("Visibility", "1");
  x.close();
  x.open("representations", "ScalarBarWidgetRepresentation", scalar_bar_id(v), 21);
  x.proxies("LookupTable", {lut});
  x.value("Title", view.array);
  x.value("ComponentTitle", s.components.at(view.array) > 1 ? "Magnitude" : "");
  x.value("Visibility", "1");
  x.value("Enabled", "1");
  x.close();
}

// The layout: a binary tree of side-by-side splits in heap order (cell i has children 2i + 1
// and 2i + 2; vtkSMViewLayoutProxy's format), n views in equal widths.
struct LayoutCell {
  int direction = 0;  // 0: a view, 2: split side by side
  double fraction = 0.5;
  int view = 0;
};

void split_views(std::vector<LayoutCell>& cells, std::size_t i, std::size_t first, std::size_t n) {
  if (cells.size() <= i) cells.resize(i + 1);
  if (n == 1) {
    cells[i].view = view_id(first);
    return;
  }
  const std::size_t left = n / 2;
  cells[i] = {2, static_cast<double>(left) / static_cast<double>(n), 0};
  split_views(cells, 2 * i + 1, first, left);
  split_views(cells, 2 * i + 2, first + left, n - left);
}

std::string layout_xml(std::size_t views) {
  std::vector<LayoutCell> cells;
  split_views(cells, 0, 0, views);
  std::string s = "      <Layout number_of_elements=\"" + std::to_string(cells.size()) + "\">\n";
  for (const LayoutCell& c : cells)
    s += "        <Item direction=\"" + std::to_string(c.direction) + "\" fraction=\"" + num(c.fraction) +
         "\" view=\"" + std::to_string(c.view) + "\"/>\n";
  return s + "      </Layout>\n";
}

// The layout of the views, the time keeper on the readers' time steps and the animation scene
// that plays them, opened on `last_time`.
void write_layout_and_time(StateXml& x, const std::vector<int>& reader_ids, const std::vector<int>& view_ids,
                           double last_time) {
  x.open("misc", "ViewLayout", kLayout, 16);
  x.raw(layout_xml(view_ids.size()));
  x.close();
  x.open("misc", "TimeKeeper", kTimeKeeper, 16);
  x.proxies("TimeSources", reader_ids);
  x.proxies("Views", view_ids);
  x.numbers("Time", {last_time});
  x.close();
  x.open("animation", "AnimationScene", kScene, 16);
  x.proxies("Cues", {kCue});
  x.proxies("TimeKeeper", {kTimeKeeper});
  x.proxies("ViewModules", view_ids);
  x.value("PlayMode", "2");  // snap to the series' time steps
  x.numbers("AnimationTime", {last_time});  // open on the last frame: the run's end state
  x.close();
  x.open("animation", "TimeAnimationCue", kCue, 16);
  x.proxies("AnimatedProxy", {kTimeKeeper});
  x.value("AnimatedPropertyName", "Time");
  x.close();
}

}  // namespace

void write_paraview_state(const fs::path& state_file, const std::vector<ParaViewView>& views) {
  if (views.empty()) throw std::invalid_argument("write_paraview_state: no views");
  const fs::path dir = state_file.parent_path().empty() ? fs::path(".") : state_file.parent_path();
  std::vector<fs::path> pvds;  // one reader per distinct series
  std::vector<std::string> luts;  // one colour map per distinct array
  for (const auto& v : views) {
    if (v.series.is_absolute()) throw std::invalid_argument("write_paraview_state: absolute path " + v.series.string());
    if (v.association != ArrayAssociation::points) throw std::invalid_argument("write_paraview_state: cell data");
    if (std::find(pvds.begin(), pvds.end(), v.series) == pvds.end()) pvds.push_back(v.series);
    if (std::find(luts.begin(), luts.end(), v.array) == luts.end()) luts.push_back(v.array);
  }
  std::vector<Series> series;
  for (const auto& p : pvds) {
    std::vector<std::string> arrays;
    for (const auto& v : views)
      if (v.series == p) arrays.push_back(v.array);
    series.push_back(scan_series(dir, p, arrays));
  }
  const auto index = [](const auto& list, const auto& x) {
    return static_cast<std::size_t>(std::find(list.begin(), list.end(), x) - list.begin());
  };
  double last_time = -std::numeric_limits<double>::infinity();
  for (const Series& sr : series) last_time = std::max(last_time, sr.frames.back().first);
  StateXml x;
  std::vector<std::pair<int, std::string>> sources, lut_items, reps, bars, view_items;
  std::vector<int> reader_ids, view_ids;
  for (std::size_t k = 0; k < pvds.size(); ++k) {
    x.open("sources", "PVDReader", reader_id(k), 1);
    x.value("FileName", pvds[k].generic_string());
    x.close();
    sources.push_back({reader_id(k), pvds[k].filename().string()});
    reader_ids.push_back(reader_id(k));
  }
  for (std::size_t k = 0; k < luts.size(); ++k) {
    std::vector<double> values;
    for (const Series& sr : series)
      if (sr.samples.count(luts[k])) values.insert(values.end(), sr.samples.at(luts[k]).begin(), sr.samples.at(luts[k]).end());
    write_lut(x, lut_id(k), colour_range(std::move(values)));
    lut_items.push_back({lut_id(k), luts[k] + ".PVLookupTable"});
  }
  for (std::size_t v = 0; v < views.size(); ++v) {
    const std::size_t k = index(pvds, views[v].series);
    write_representation(x, v, reader_id(k), lut_id(index(luts, views[v].array)), views[v], series[k]);
    write_view(x, v, series[k], views.size());
    reps.push_back({representation_id(v), "GeometryRepresentation" + std::to_string(v + 1)});
    bars.push_back({scalar_bar_id(v), "ScalarBarWidgetRepresentation" + std::to_string(v + 1)});
    view_items.push_back({view_id(v), "RenderView" + std::to_string(v + 1)});
    view_ids.push_back(view_id(v));
  }
  write_layout_and_time(x, reader_ids, view_ids, last_time);
  x.collection("animation", {{kScene, "AnimationScene1"}, {kCue, "TimeAnimationCue1"}});
  x.collection("layouts", {{kLayout, "Layout #1"}});
  x.collection("lookup_tables", lut_items);
  x.collection("representations", reps);
  x.collection("scalar_bars", bars);
  x.collection("sources", sources);
  x.collection("timekeeper", {{kTimeKeeper, "TimeKeeper1"}});
  x.collection("views", view_items);
  AtomicFile out(state_file);
  out << "<ParaView>\n  <ServerManagerState version=\"5.10.0\">\n"
      << x.text() << "  </ServerManagerState>\n</ParaView>\n";
  out.commit();
}

bool write_paraview_state_or_warn(const fs::path& state_file, const std::vector<ParaViewView>& views) {
  try {
    write_paraview_state(state_file, views);
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sphark: warning: %s: %s\n", state_file.c_str(), e.what());
    return false;
  }
}

}  // namespace sphark
