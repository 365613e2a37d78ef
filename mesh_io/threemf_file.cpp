// 3MF through lib3mf's C interface (Debian's lib3mf 1.x): what mesh_io.h says of 3MF.
//
// Reading walks the build: each item's object, through components objects down to the meshes,
// composing the transforms on the way; every mesh so placed becomes a ThreeMfPart, its vertices
// moved onto the plate and scaled to millimetres. Writing makes one mesh object per part, with the
// part's name and transform and the file's unit, its vertices taken back from the plate into the
// object's own coordinates, so that a slicer places each object where it was.
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "Model/COM/NMR_DLLInterfaces.h"
#include "mesh_io/mesh_formats.h"
#include "vcg_adapters/quality_ramp.h"

namespace slim::io::detail {

namespace {

using Transform = Eigen::Matrix<double, 3, 4>;

// lib3mf's handles, and the same released when it goes out of scope.
using Object = NMR::PLib3MFBase*;
struct Release {
  void operator()(Object handle) const { NMR::lib3mf_release(handle); }
};
using Handle = std::unique_ptr<NMR::PLib3MFBase, Release>;

// lib3mf's message for its last error on `instance`, or a generic one.
std::string last_error(Object instance, LIB3MFRESULT code) {
  DWORD error = 0;
  LPCSTR message = nullptr;
  if (instance && NMR::lib3mf_getlasterror(instance, &error, &message) == LIB3MF_OK && message && *message)
    return message;
  return "lib3mf error " + std::to_string(code);
}

// Runs a lib3mf call; a failure throws "<what>: <lib3mf's reason>".
void check(LIB3MFRESULT code, Object instance, const std::string& what) {
  if (code != LIB3MF_OK) throw std::runtime_error(what + ": " + last_error(instance, code));
}

// A handle lib3mf hands out through `get(from, &handle)`.
template <class Get>
Handle obtain(Get get, Object from, const char* what) {
  Object raw = nullptr;
  check(get(from, &raw), from, what);
  return Handle(raw);
}

double millimetres_per(DWORD unit) {
  switch (unit) {
    case NMR::MODELUNIT_MICROMETER: return 0.001;
    case NMR::MODELUNIT_MILLIMETER: return 1.0;
    case NMR::MODELUNIT_CENTIMETER: return 10.0;
    case NMR::MODELUNIT_INCH: return 25.4;
    case NMR::MODELUNIT_FOOT: return 304.8;
    case NMR::MODELUNIT_METER: return 1000.0;
  }
  throw std::runtime_error("an unknown unit (" + std::to_string(unit) + ")");
}

Transform from_lib3mf(const NMR::MODELTRANSFORM& t) {
  Transform m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = t.m_fFields[r][c];
  return m;
}

// The transform as lib3mf writes it: each field as a float, printed to 6 significant digits.
Transform as_written(const Transform& m) {
  Transform w;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      std::ostringstream text;
      text << static_cast<float>(m(r, c));
      w(r, c) = std::stod(text.str());
    }
  return w;
}

NMR::MODELTRANSFORM to_lib3mf(const Transform& m) {
  NMR::MODELTRANSFORM t;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) t.m_fFields[r][c] = static_cast<float>(m(r, c));
  return t;
}

// outer after inner: x -> outer(inner(x)).
Transform compose(const Transform& outer, const Transform& inner) {
  Transform m;
  m.leftCols<3>() = outer.leftCols<3>() * inner.leftCols<3>();
  m.col(3) = outer.leftCols<3>() * inner.col(3) + outer.col(3);
  return m;
}

std::string object_name(Object object) {
  ULONG needed = 0;
  if (NMR::lib3mf_object_getnameutf8(object, nullptr, 0, &needed) != LIB3MF_OK || needed == 0) return "";
  std::string name(needed + 1, '\0');  // lib3mf counts the characters and wants room for the end too
  if (NMR::lib3mf_object_getnameutf8(object, name.data(), needed + 1, &needed) != LIB3MF_OK) return "";
  name.resize(needed);
  return name;
}

// The meshes a build places, gathered into one surface in plate millimetres.
struct Gathered {
  std::vector<Eigen::RowVector3d> V;
  std::vector<Eigen::RowVector3i> F;
  ThreeMfBuild build;
};

void gather_mesh(Object mesh, const Transform& placement, Gathered& g) {
  DWORD nv = 0, nf = 0;
  check(NMR::lib3mf_meshobject_getvertexcount(mesh, &nv), mesh, "its vertex count");
  check(NMR::lib3mf_meshobject_gettrianglecount(mesh, &nf), mesh, "its triangle count");
  std::vector<NMR::MODELMESHVERTEX> vertices(nv);
  std::vector<NMR::MODELMESHTRIANGLE> triangles(nf);
  if (nv > 0) check(NMR::lib3mf_meshobject_getvertices(mesh, vertices.data(), nv, nullptr), mesh, "its vertices");
  if (nf > 0) check(NMR::lib3mf_meshobject_gettriangleindices(mesh, triangles.data(), nf, nullptr), mesh, "its triangles");
  if (!(std::abs(placement.leftCols<3>().determinant()) > 1e-12))
    throw std::runtime_error("object \"" + object_name(mesh) + "\" is placed by a singular transform");
  ThreeMfPart part{object_name(mesh), static_cast<Eigen::Index>(g.V.size()), nv,
                   static_cast<Eigen::Index>(g.F.size()), nf, placement};
  const double mm = g.build.millimetres_per_unit;
  for (const NMR::MODELMESHVERTEX& v : vertices) {
    const Eigen::Vector3d p(v.m_fPosition[0], v.m_fPosition[1], v.m_fPosition[2]);
    g.V.push_back(mm * (placement.leftCols<3>() * p + placement.col(3)).transpose());
  }
  for (const NMR::MODELMESHTRIANGLE& t : triangles) {
    Eigen::RowVector3i f;
    for (int k = 0; k < 3; ++k) {
      if (t.m_nIndices[k] >= nv)
        throw std::runtime_error("object \"" + part.name + "\" has a triangle with vertex " + std::to_string(t.m_nIndices[k]) +
                                 " of " + std::to_string(nv));
      f(k) = static_cast<int>(part.first_vertex + t.m_nIndices[k]);
    }
    g.F.push_back(f);
  }
  g.build.parts.push_back(part);
}

// An object of the build: a mesh, or components each placing another object.
void gather_object(Object object, const Transform& placement, int depth, Gathered& g) {
  if (depth > 32) throw std::runtime_error("its components nest deeper than 32 levels (a cycle?)");
  BOOL is_mesh = 0, is_components = 0;
  check(NMR::lib3mf_object_ismeshobject(object, &is_mesh), object, "an object's type");
  check(NMR::lib3mf_object_iscomponentsobject(object, &is_components), object, "an object's type");
  if (is_mesh) return gather_mesh(object, placement, g);
  if (!is_components) return;
  DWORD count = 0;
  check(NMR::lib3mf_componentsobject_getcomponentcount(object, &count), object, "its components");
  for (DWORD i = 0; i < count; ++i) {
    const Handle component = obtain([i](Object o, Object* c) { return NMR::lib3mf_componentsobject_getcomponent(o, i, c); },
                                    object, "a component");
    const Handle inner = obtain(NMR::lib3mf_component_getobjectresource, component.get(), "a component's object");
    NMR::MODELTRANSFORM t;
    check(NMR::lib3mf_component_gettransform(component.get(), &t), component.get(), "a component's transform");
    gather_object(inner.get(), compose(placement, from_lib3mf(t)), depth + 1, g);
  }
}

void gather_build(Object model, Gathered& g) {
  const Handle items = obtain(NMR::lib3mf_model_getbuilditems, model, "its build");
  BOOL more = 0;
  for (check(NMR::lib3mf_builditemiterator_movenext(items.get(), &more), items.get(), "its build"); more;
       check(NMR::lib3mf_builditemiterator_movenext(items.get(), &more), items.get(), "its build")) {
    const Handle item = obtain(NMR::lib3mf_builditemiterator_getcurrent, items.get(), "a build item");
    const Handle object = obtain(NMR::lib3mf_builditem_getobjectresource, item.get(), "a build item's object");
    NMR::MODELTRANSFORM t;
    check(NMR::lib3mf_builditem_getobjecttransform(item.get(), &t), item.get(), "a build item's transform");
    gather_object(object.get(), from_lib3mf(t), 0, g);
  }
}

Handle new_model() {
  Object model = nullptr;
  const LIB3MFRESULT code = NMR::lib3mf_createmodel(&model);
  if (code != LIB3MF_OK) throw std::runtime_error("lib3mf cannot make a model (error " + std::to_string(code) + ")");
  return Handle(model);
}

}  // namespace

MeshFile read_3mf(const std::string& path, const std::string& bytes) {
  Gathered g;
  try {
    const Handle model = new_model();
    Object raw = nullptr;
    check(NMR::lib3mf_model_queryreader(model.get(), "3mf", &raw), model.get(), "no 3MF reader");
    const Handle reader(raw);
    const std::string package = readable_3mf_package(bytes);
    std::vector<BYTE> buffer(package.begin(), package.end());
    check(NMR::lib3mf_reader_readfrombuffer(raw, buffer.data(), buffer.size()), raw, "not a readable 3MF file");
    DWORD unit = 0;
    check(NMR::lib3mf_model_getunit(model.get(), &unit), model.get(), "its unit");
    g.build.unit = static_cast<int>(unit);
    g.build.millimetres_per_unit = millimetres_per(unit);
    gather_build(model.get(), g);
  } catch (const std::exception& e) {
    refuse(path, e.what());
  }
  if (g.F.empty()) refuse(path, "its build places no triangles");
  MeshFile file;
  file.format = MeshFormat::ThreeMf;
  check_count(path, "vertices", g.V.size(), 0, 0);
  file.surface.V.resize(static_cast<Eigen::Index>(g.V.size()), 3);
  file.surface.F.resize(static_cast<Eigen::Index>(g.F.size()), 3);
  for (size_t i = 0; i < g.V.size(); ++i) file.surface.V.row(static_cast<Eigen::Index>(i)) = g.V[i];
  for (size_t i = 0; i < g.F.size(); ++i) file.surface.F.row(static_cast<Eigen::Index>(i)) = g.F[i];
  file.build = std::move(g.build);
  return file;
}

namespace {

// One part as a mesh object: the plate's vertices taken back into the object's own coordinates,
// its triangles coloured on the quality ramp when `quality` is given.
void add_part(Object model, const ThreeMfPart& part, double mm_per_unit, const Surface& plate, const Eigen::VectorXd& quality) {
  Object raw = nullptr;
  check(NMR::lib3mf_model_addmeshobject(model, &raw), model, "adding an object");
  const Handle mesh(raw);
  // The vertices are taken back through the transform the file will hold, so that the slicer puts
  // them where the plate has them, not where the rounding of the transform would.
  const Transform placement = as_written(part.transform);
  const Eigen::Matrix3d back = placement.leftCols<3>().inverse();
  std::vector<NMR::MODELMESHVERTEX> vertices(static_cast<size_t>(part.vertex_count));
  for (Eigen::Index i = 0; i < part.vertex_count; ++i) {
    const Eigen::Vector3d p = back * (plate.V.row(part.first_vertex + i).transpose() / mm_per_unit - placement.col(3));
    for (int k = 0; k < 3; ++k) vertices[static_cast<size_t>(i)].m_fPosition[k] = static_cast<float>(p(k));
  }
  std::vector<NMR::MODELMESHTRIANGLE> triangles(static_cast<size_t>(part.face_count));
  for (Eigen::Index f = 0; f < part.face_count; ++f)
    for (int k = 0; k < 3; ++k)
      triangles[static_cast<size_t>(f)].m_nIndices[k] = static_cast<DWORD>(plate.F(part.first_face + f, k) - part.first_vertex);
  check(NMR::lib3mf_meshobject_setgeometry(raw, vertices.data(), static_cast<DWORD>(vertices.size()), triangles.data(),
                                           static_cast<DWORD>(triangles.size())),
        raw, "setting an object's mesh");
  if (!part.name.empty()) check(NMR::lib3mf_object_setnameutf8(raw, part.name.c_str()), raw, "naming an object");
  if (quality.size() > 0) {
    Object raw_handler = nullptr;
    check(NMR::lib3mf_meshobject_createpropertyhandler(raw, &raw_handler), raw, "colouring an object");
    const Handle handler(raw_handler);
    for (Eigen::Index f = 0; f < part.face_count; ++f) {
      const auto c = vcg_adapters::quality_ramp_colour(quality(part.first_face + f));
      check(NMR::lib3mf_propertyhandler_setsinglecolorrgb(raw_handler, static_cast<DWORD>(f), c(0), c(1), c(2)),
            raw_handler, "colouring a triangle");
    }
    // 3MF asks an object with triangle colours for a default one: the ramp's at a safe face.
    Object raw_default = nullptr;
    check(NMR::lib3mf_object_createdefaultpropertyhandler(raw, &raw_default), raw, "colouring an object");
    const Handle default_handler(raw_default);
    const auto c = vcg_adapters::quality_ramp_colour(vcg_adapters::kQualityRampMax);
    check(NMR::lib3mf_defaultpropertyhandler_setcolorrgb(raw_default, c(0), c(1), c(2)), raw_default, "colouring an object");
  }
  NMR::MODELTRANSFORM t = to_lib3mf(placement);
  Object raw_item = nullptr;
  check(NMR::lib3mf_model_addbuilditem(model, raw, &t, &raw_item), model, "placing an object");
  const Handle item(raw_item);
}

// The parts to write: the source's own build, or (from another format) the whole surface as one
// object in millimetres where it is.
ThreeMfBuild build_to_write(const MeshFile& source, const std::string& path) {
  if (!source.build.parts.empty()) return source.build;
  ThreeMfBuild one;
  const size_t slash = path.find_last_of('/'), dot = path.find_last_of('.');
  const size_t start = slash == std::string::npos ? 0 : slash + 1;
  one.parts.push_back({path.substr(start, dot == std::string::npos || dot < start ? std::string::npos : dot - start), 0,
                       source.surface.V.rows(), 0, source.surface.F.rows(), Transform::Identity()});
  return one;
}

}  // namespace

void write_3mf(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results) {
  const ThreeMfBuild build = build_to_write(source, path);
  const Surface plate{V, source.surface.F};
  try {
    const Handle model = new_model();
    check(NMR::lib3mf_model_setunit(model.get(), static_cast<DWORD>(build.unit)), model.get(), "setting the unit");
    for (const ThreeMfPart& part : build.parts) add_part(model.get(), part, build.millimetres_per_unit, plate, results.quality);
    Object raw = nullptr;
    check(NMR::lib3mf_model_querywriter(model.get(), "3mf", &raw), model.get(), "no 3MF writer");
    const Handle writer(raw);
    check(NMR::lib3mf_writer_writetofileutf8(raw, path.c_str()), raw, "writing failed");
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write " + path + ": " + e.what());
  }
}

}  // namespace slim::io::detail
