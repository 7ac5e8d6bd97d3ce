#include "sphark/io/vtp_reader.hpp"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPPolyDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <stdexcept>

namespace sphark {

const VtpArray* VtpContents::find(const std::string& name) const {
  for (const auto& a : arrays) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

namespace {

VtpContents contents(vtkPolyData* poly) {
  VtpContents out;
  out.count = static_cast<std::size_t>(poly->GetNumberOfPoints());
  out.vertex_cells = static_cast<std::size_t>(poly->GetNumberOfVerts());
  out.points.resize(3 * out.count);
  for (std::size_t i = 0; i < out.count; ++i) {
    poly->GetPoint(static_cast<vtkIdType>(i), &out.points[3 * i]);
  }
  vtkPointData* pd = poly->GetPointData();
  for (int k = 0; k < pd->GetNumberOfArrays(); ++k) {
    vtkDataArray* a = pd->GetArray(k);
    if (!a) continue;
    VtpArray arr;
    arr.name = a->GetName() ? a->GetName() : "";
    arr.components = a->GetNumberOfComponents();
    arr.values.resize(out.count * static_cast<std::size_t>(arr.components));
    for (std::size_t i = 0; i < out.count; ++i) {
      for (int c = 0; c < arr.components; ++c) {
        arr.values[i * arr.components + c] = a->GetComponent(static_cast<vtkIdType>(i), c);
      }
    }
    out.arrays.push_back(std::move(arr));
  }
  if (vtkDataArray* t = poly->GetFieldData()->GetArray("TimeValue");
      t && t->GetNumberOfTuples() > 0) {
    out.time = t->GetComponent(0, 0);
  }
  return out;
}

// Reads `path` with a VTK XML reader (serial or parallel poly data); `what` names the function.
template <class Reader>
VtpContents read_with(const std::filesystem::path& path, const std::string& what, const char* kind) {
  if (!std::filesystem::is_regular_file(path)) {
    throw std::runtime_error(what + ": no file '" + path.string() + "'");
  }
  vtkNew<Reader> reader;
  if (!reader->CanReadFile(path.c_str())) {
    throw std::runtime_error(what + ": '" + path.string() + "' is not a readable " + kind);
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  if (reader->GetErrorCode() != 0) {
    throw std::runtime_error(what + ": error reading '" + path.string() + "'");
  }
  return contents(reader->GetOutput());
}

}  // namespace

VtpContents read_vtp(const std::filesystem::path& path) {
  return read_with<vtkXMLPolyDataReader>(path, "read_vtp", ".vtp");
}

VtpContents read_pvtp(const std::filesystem::path& path) {
  return read_with<vtkXMLPPolyDataReader>(path, "read_pvtp", ".pvtp");
}

VtpContents read_frame(const std::filesystem::path& path) {
  return path.extension() == ".pvtp" ? read_pvtp(path) : read_vtp(path);
}

}  // namespace sphark
