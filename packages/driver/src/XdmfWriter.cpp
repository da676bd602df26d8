#include "gphr/driver/XdmfWriter.hpp"

#include <sstream>

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {

// Text as XML attribute or element content: a file name may hold any of these.
std::string xmlEscaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// The grid as XDMF's 3-D order (z, y, x), missing directions one point wide.
struct Zyx {
  GO points[3] = {1, 1, 1};
  double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1};
};
Zyx zyx(const SceneGrid& g) {
  Zyx out;
  for (size_t d = 0; d < g.points.size(); ++d) {
    const size_t z = 2 - d;
    out.points[z] = g.points[d], out.origin[z] = g.origin[d], out.spacing[z] = g.spacing[d];
  }
  return out;
}

// One time's grid: topology, geometry and the fields of every dataset at row j.
void timeGrid(std::ostream& os, const SceneGrid& grid, const std::string& h5, size_t rows, size_t j, double t,
              const std::vector<XdmfStates>& states) {
  const Zyx g = zyx(grid);
  const GO n = grid.numPoints(), width = n * static_cast<GO>(grid.components.size());
  os << "      <Grid Name=\"t" << j << "\" GridType=\"Uniform\">\n"
     << "        <Time Value=\"" << t << "\"/>\n"
     << "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << g.points[0] << " " << g.points[1] << " "
     << g.points[2] << "\"/>\n"
     << "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
     << "          <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">" << g.origin[0] << " "
     << g.origin[1] << " " << g.origin[2] << "</DataItem>\n"
     << "          <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">" << g.spacing[0]
     << " " << g.spacing[1] << " " << g.spacing[2] << "</DataItem>\n"
     << "        </Geometry>\n";
  for (const auto& s : states)
    for (size_t c = 0; c < grid.components.size(); ++c) {
      // start (j, c n), stride (1, 1), count (1, n) of the (rows, width) dataset, shaped as the
      // grid: ParaView's XDMF Reader takes the first nx values of a hyperslab shaped (1, n)
      os << "        <Attribute Name=\"" << xmlEscaped(grid.components[c] + "_" + s.name)
         << "\" AttributeType=\"Scalar\" Center=\"Node\">\n"
         << "          <DataItem ItemType=\"HyperSlab\" Dimensions=\"" << g.points[0] << " " << g.points[1] << " "
         << g.points[2] << "\" Type=\"HyperSlab\">\n"
         << "            <DataItem Dimensions=\"3 2\" NumberType=\"Int\" Format=\"XML\">" << j << " " << c * n
         << " 1 1 1 " << n << "</DataItem>\n"
         << "            <DataItem Dimensions=\"" << rows << " " << width
         << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << xmlEscaped(h5 + ":" + s.dataset)
         << "</DataItem>\n"
         << "          </DataItem>\n"
         << "        </Attribute>\n";
    }
  os << "      </Grid>\n";
}

}  // namespace

SceneGrid fieldGrid(const Scene& scene, GO fullDim) {
  const auto grid = scene.grid();
  GPHR_REQUIRE(grid.has_value(), InputError, "scene '", scene.name(),
               "' declares no grid (Scene::grid): its states cannot be drawn or written for ParaView; "
               "declare the grid's points, origin, spacing and component names to get them");
  grid->check(fullDim, scene.name());
  return *grid;
}

std::string fieldName(const std::string& label) {
  std::string out;
  for (char c : label)
    if (c == ' ') out += '_';
    else if (c != '=') out += c;
  return out;
}

std::string xdmfText(const SceneGrid& grid, const std::string& h5File, const std::vector<double>& times,
                     const std::vector<XdmfStates>& states) {
  std::ostringstream os;
  os.precision(17);
  os << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n  <Domain>\n"
     << "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (size_t j = 0; j < times.size(); ++j) timeGrid(os, grid, h5File, times.size(), j, times[j], states);
  os << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return os.str();
}

}  // namespace gphr
