// run.xdmf: the light-data index ParaView opens; all heavy data stays in run.h5.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace rockcut::coupler {

struct XdmfField {
  std::string name;    ///< dataset name inside the frame group
  int components = 1;  ///< 1 (Scalar) or 2 (Vector)
};

struct XdmfFrame {
  std::string group;  ///< e.g. "/frames/000003"
  double time_s = 0.0;
  std::size_t particle_count = 0;
  std::vector<XdmfField> fields;  ///< includes "position" (the geometry)
};

/// Builds the whole document from frame metadata; the file is rewritten (atomically) after every
/// frame so a run that stops early still leaves a consistent index.
class XdmfWriter {
 public:
  /// `h5_name` is the HDF5 file name relative to the XDMF file ("run.h5"); `vertex_ids` is the
  /// path of the int32 dataset 0, 1, 2, ... in it that the topologies select from.
  XdmfWriter(std::filesystem::path xdmf_path, std::string h5_name, std::string vertex_ids);

  void add_frame(XdmfFrame frame);
  /// `vertex_id_count` is the current length of the vertex-id dataset (>= every frame's count).
  std::string document(std::size_t vertex_id_count) const;
  void write(std::size_t vertex_id_count) const;

 private:
  std::filesystem::path path_;
  std::string h5_name_;
  std::string vertex_ids_;
  std::vector<XdmfFrame> frames_;
};

/// Escapes &, <, >, " and ' for use in XML text and attribute values.
std::string xml_escape(const std::string& text);

}  // namespace rockcut::coupler
