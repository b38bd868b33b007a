#include "output/xdmf_writer.hpp"

#include <charconv>
#include <cmath>
#include <utility>

#include "output/atomic_write.hpp"

// Layout choices, for ParaView (its "Xdmf3 Reader" and the legacy "XDMF Reader"):
//  * One Uniform grid per frame inside a Temporal collection; each grid carries its <Time>.
//  * Topology: Polyvertex with NumberOfElements = n and NodesPerElement = 1, WITH explicit
//    connectivity. The Xdmf3 library computes the cell count as connectivity size / nodes per
//    element, so a Polyvertex without a DataItem gives points but no cells (nothing to render in
//    Surface/Points mode). The connectivity is a HyperSlab selecting the first n entries of one
//    shared dataset 0, 1, 2, ... (run.h5:/xdmf/vertex_ids) instead of n ids per frame.
//  * Geometry: XY from /frames/NNNNNN/position (n 2); the readers pad z = 0.
//  * 2-component fields: AttributeType="Vector" with Dimensions "n 2". The Xdmf3 reader takes the
//    component count from the data (values / points), so velocity/force arrive as correct
//    2-component point arrays (colour by magnitude or X/Y works). VTK only marks 3-component
//    arrays as the active vectors, so for Glyph orientation make a 3-vector with a Calculator
//    (velocity_X*iHat + velocity_Y*jHat). Padding via an XDMF JOIN function would avoid that step
//    but depends on the function parser of each reader; plain HDF references are the portable
//    choice. Prefer the Xdmf3 reader: the legacy reader may assume 3 components for Vector.
//  * Frames with zero particles have no datasets and are left out of the collection.

namespace rockcut::coupler {

namespace {

std::string format_double(double value) {
  if (!std::isfinite(value)) return "0";  // RunFile rejects such times; keep the XML valid anyway
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, 17);
  return std::string(buf, result.ptr);
}

void append_hdf_item(std::string& out, const std::string& indent, const std::string& dims,
                     const char* number_type, int precision, const std::string& reference) {
  out += indent + "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + number_type +
         "\" Precision=\"" + std::to_string(precision) + "\" Format=\"HDF\">" +
         xml_escape(reference) + "</DataItem>\n";
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

XdmfWriter::XdmfWriter(std::filesystem::path xdmf_path, std::string h5_name,
                       std::string vertex_ids)
    : path_(std::move(xdmf_path)), h5_name_(std::move(h5_name)),
      vertex_ids_(std::move(vertex_ids)) {}

void XdmfWriter::add_frame(XdmfFrame frame) { frames_.push_back(std::move(frame)); }

std::string XdmfWriter::document(std::size_t vertex_id_count) const {
  std::string out;
  out.reserve(512 + frames_.size() * 1024);
  out += "<?xml version=\"1.0\" ?>\n";
  out += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  out += "<Xdmf Version=\"3.0\">\n";
  out += "  <Domain>\n";
  out += "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const std::string ids_dims = std::to_string(vertex_id_count);
  for (const XdmfFrame& frame : frames_) {
    if (frame.particle_count == 0) continue;
    const std::string n = std::to_string(frame.particle_count);
    const std::string base = h5_name_ + ":" + frame.group + "/";
    const std::string name = frame.group.substr(frame.group.find_last_of('/') + 1);
    out += "      <Grid Name=\"frame_" + xml_escape(name) + "\" GridType=\"Uniform\">\n";
    out += "        <Time Value=\"" + format_double(frame.time_s) + "\"/>\n";
    out += "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + n +
           "\" NodesPerElement=\"1\">\n";
    // HyperSlab: the first item holds start / stride / count, the second the selected data.
    out += "          <DataItem ItemType=\"HyperSlab\" Dimensions=\"" + n +
           "\" Type=\"HyperSlab\">\n";
    out += "            <DataItem Dimensions=\"3 1\" NumberType=\"Int\" Format=\"XML\">0 1 " + n +
           "</DataItem>\n";
    append_hdf_item(out, "            ", ids_dims, "Int", 4, h5_name_ + ":" + vertex_ids_);
    out += "          </DataItem>\n";
    out += "        </Topology>\n";
    out += "        <Geometry GeometryType=\"XY\">\n";
    append_hdf_item(out, "          ", n + " 2", "Float", 8, base + "position");
    out += "        </Geometry>\n";
    for (const XdmfField& field : frame.fields) {
      if (field.name == "position") continue;
      const bool vector = field.components == 2;
      out += "        <Attribute Name=\"" + xml_escape(field.name) + "\" AttributeType=\"" +
             (vector ? "Vector" : "Scalar") + "\" Center=\"Node\">\n";
      append_hdf_item(out, "          ", vector ? n + " 2" : n, "Float", 8, base + field.name);
      out += "        </Attribute>\n";
    }
    out += "      </Grid>\n";
  }
  out += "    </Grid>\n";
  out += "  </Domain>\n";
  out += "</Xdmf>\n";
  return out;
}

void XdmfWriter::write(std::size_t vertex_id_count) const {
  write_file_atomically(path_, document(vertex_id_count));
}

}  // namespace rockcut::coupler
