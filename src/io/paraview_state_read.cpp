// Reading back what a ParaView state and a .pvd collection name (VTK's XML parser).
#include <vtkXMLDataElement.h>
#include <vtkXMLUtilities.h>

#include <charconv>
#include <map>
#include <memory>
#include <stdexcept>

#include "sphark/io/paraview_state.hpp"

namespace sphark {

namespace fs = std::filesystem;

namespace {

struct ElementDeleter {
  void operator()(vtkXMLDataElement* e) const {
    if (e) e->Delete();
  }
};
using Element = std::unique_ptr<vtkXMLDataElement, ElementDeleter>;

Element read_xml(const fs::path& file, const char* what) {
  if (!fs::is_regular_file(file)) throw std::runtime_error(std::string(what) + ": no file '" + file.string() + "'");
  Element root(vtkXMLUtilities::ReadElementFromFile(file.c_str()));
  if (!root) throw std::runtime_error(std::string(what) + ": '" + file.string() + "' is not well-formed XML");
  return root;
}

std::string attribute(vtkXMLDataElement* e, const char* name) {
  const char* v = e->GetAttribute(name);
  return v ? v : "";
}

// The <Property name=...> of a <Proxy>, or nullptr.
vtkXMLDataElement* property(vtkXMLDataElement* proxy, const std::string& name) {
  for (int i = 0; i < proxy->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* p = proxy->GetNestedElement(i);
    if (std::string(p->GetName()) == "Property" && attribute(p, "name") == name) return p;
  }
  return nullptr;
}

// The value attributes of a property's <Element>s (or of its <Proxy>s), in index order.
std::vector<std::string> values(vtkXMLDataElement* prop, const char* child) {
  std::vector<std::string> out;
  if (!prop) return out;
  for (int i = 0; i < prop->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = prop->GetNestedElement(i);
    if (std::string(e->GetName()) == child) out.push_back(attribute(e, "value"));
  }
  return out;
}

double number(const std::string& s) {
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) throw std::runtime_error("read_paraview_state: bad number '" + s + "'");
  return v;
}

}  // namespace

std::vector<std::pair<Real, std::string>> read_pvd(const fs::path& pvd) {
  Element root = read_xml(pvd, "read_pvd");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  if (std::string(root->GetName()) != "VTKFile" || !collection)
    throw std::runtime_error("read_pvd: '" + pvd.string() + "' is not a VTK collection");
  std::vector<std::pair<Real, std::string>> frames;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* d = collection->GetNestedElement(i);
    if (std::string(d->GetName()) != "DataSet") continue;
    const std::string t = attribute(d, "timestep"), file = attribute(d, "file");
    Real time = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), time);
    if (file.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
      throw std::runtime_error("read_pvd: '" + pvd.string() + "': a DataSet without a timestep or file");
    frames.emplace_back(time, file);
  }
  return frames;
}

ParaViewStateRefs read_paraview_state(const fs::path& state_file) {
  Element root = read_xml(state_file, "read_paraview_state");
  vtkXMLDataElement* sm = root->FindNestedElementWithName("ServerManagerState");
  if (std::string(root->GetName()) != "ParaView" || !sm)
    throw std::runtime_error("read_paraview_state: '" + state_file.string() + "' has no ServerManagerState");
  std::map<std::string, vtkXMLDataElement*> proxies;  // by id
  for (int i = 0; i < sm->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = sm->GetNestedElement(i);
    if (std::string(e->GetName()) == "Proxy") proxies[attribute(e, "id")] = e;
  }
  const auto fail = [&](const std::string& why) {
    throw std::runtime_error("read_paraview_state: '" + state_file.string() + "': " + why);
  };
  ParaViewStateRefs refs;
  for (const auto& [id, p] : proxies) {
    const std::string type = attribute(p, "type");
    if (type == "PVDReader") {
      const auto f = values(property(p, "FileName"), "Element");
      if (f.size() != 1) fail("reader " + id + " without one FileName");
      refs.files.push_back(f[0]);
    } else if (type == "RenderView") {
      ++refs.views;
    } else if (type == "ViewLayout") {
      vtkXMLDataElement* layout = p->FindNestedElementWithName("Layout");
      for (int i = 0; layout && i < layout->GetNumberOfNestedElements(); ++i) {
        const std::string v = attribute(layout->GetNestedElement(i), "view");
        if (v != "0" && !v.empty()) {
          if (!proxies.count(v) || attribute(proxies[v], "type") != "RenderView") fail("layout names no view " + v);
          ++refs.layout_views;
        }
      }
    } else if (attribute(p, "group") == "representations" && property(p, "ColorArrayName")) {
      const auto colour = values(property(p, "ColorArrayName"), "Element");
      const auto input = values(property(p, "Input"), "Proxy");
      const auto lut = values(property(p, "LookupTable"), "Proxy");
      if (colour.size() != 5) fail("representation " + id + ": ColorArrayName without 5 elements");
      if (input.size() != 1 || !proxies.count(input[0])) fail("representation " + id + " shows no reader");
      if (lut.size() != 1 || !proxies.count(lut[0])) fail("representation " + id + " has no colour map");
      const auto file = values(property(proxies[input[0]], "FileName"), "Element");
      const auto rgb = values(property(proxies[lut[0]], "RGBPoints"), "Element");
      if (rgb.size() < 8 || rgb.size() % 4 != 0) fail("colour map " + lut[0] + " without RGBPoints");
      refs.colourings.push_back({colour[4], colour[3] == "0" ? "points" : colour[3] == "1" ? "cells" : colour[3],
                                 file.empty() ? "" : file[0], number(rgb.front()), number(rgb[rgb.size() - 4])});
    }
  }
  return refs;
}

}  // namespace sphark
