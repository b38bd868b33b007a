// run.xdmf: parsed as XML (a small strict parser below) and every HDF reference resolved
// against run.h5, so a grid pointing at a missing or mis-shaped dataset fails the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "output/h5_handle.hpp"
#include "output/run_file.hpp"

namespace rockcut::coupler::testing {
// Defined in h5_read_util.cpp.
std::filesystem::path scratch_dir(const std::string& name);
h5::Handle open_read_only(const std::filesystem::path& file);
std::vector<hsize_t> dataset_dims(hid_t file, const std::string& path);
std::vector<std::int32_t> read_i32s(hid_t file, const std::string& path);

namespace {

struct Element {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::string text;
  std::vector<Element> children;

  std::vector<const Element*> all(const std::string& tag) const {
    std::vector<const Element*> found;
    for (const Element& c : children) {
      if (c.name == tag) found.push_back(&c);
    }
    return found;
  }
  const Element& one(const std::string& tag) const {
    const auto found = all(tag);
    if (found.size() != 1) throw std::runtime_error(name + ": expected one <" + tag + ">");
    return *found.front();
  }
  std::string attr(const std::string& key) const {
    const auto it = attrs.find(key);
    if (it == attrs.end()) throw std::runtime_error(name + ": no attribute " + key);
    return it->second;
  }
  std::string trimmed_text() const {
    const auto b = text.find_first_not_of(" \t\r\n");
    const auto e = text.find_last_not_of(" \t\r\n");
    return b == std::string::npos ? std::string() : text.substr(b, e - b + 1);
  }
};

/// Enough XML for XDMF: prolog, DOCTYPE, comments, elements, quoted attributes, entities.
class MiniXml {
 public:
  explicit MiniXml(std::string text) : s_(std::move(text)) {}

  Element parse() {
    skip_misc();
    Element root = element();
    skip_misc();
    if (pos_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML offset " + std::to_string(pos_) + ": " + what);
  }
  bool starts(const char* p) const { return s_.compare(pos_, std::strlen(p), p) == 0; }
  void skip_ws() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  void skip_past(const char* end) {
    const auto at = s_.find(end, pos_);
    if (at == std::string::npos) fail(std::string("missing ") + end);
    pos_ = at + std::strlen(end);
  }
  void skip_misc() {
    while (true) {
      skip_ws();
      if (starts("<?")) {
        skip_past("?>");
      } else if (starts("<!--")) {
        skip_past("-->");
      } else if (starts("<!DOCTYPE")) {
        const auto bracket = s_.find('[', pos_);
        if (bracket != std::string::npos && bracket < s_.find('>', pos_)) {
          pos_ = bracket;
          skip_past("]");
        }
        skip_past(">");
      } else {
        return;
      }
    }
  }
  std::string name() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) ||
                                s_[pos_] == '_' || s_[pos_] == ':' || s_[pos_] == '-')) {
      ++pos_;
    }
    if (pos_ == start) fail("expected a name");
    return s_.substr(start, pos_ - start);
  }
  static std::string decode(const std::string& raw) {
    static const std::map<std::string, char> entities = {
        {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const auto semi = raw.find(';', i);
      const auto it = semi == std::string::npos ? entities.end()
                                                : entities.find(raw.substr(i + 1, semi - i - 1));
      if (it == entities.end()) throw std::runtime_error("bad entity in: " + raw);
      out += it->second;
      i = semi;
    }
    return out;
  }
  Element element() {
    if (!starts("<")) fail("expected '<'");
    ++pos_;
    Element e;
    e.name = name();
    while (true) {
      skip_ws();
      if (starts("/>")) {
        pos_ += 2;
        return e;
      }
      if (starts(">")) {
        ++pos_;
        break;
      }
      const std::string key = name();
      skip_ws();
      if (!starts("=")) fail("expected '='");
      ++pos_;
      skip_ws();
      const char quote = pos_ < s_.size() ? s_[pos_] : '\0';
      if (quote != '"' && quote != '\'') fail("expected a quoted value");
      const auto end = s_.find(quote, pos_ + 1);
      if (end == std::string::npos) fail("unterminated attribute value");
      if (!e.attrs.emplace(key, decode(s_.substr(pos_ + 1, end - pos_ - 1))).second) {
        fail("duplicate attribute " + key);
      }
      pos_ = end + 1;
    }
    while (true) {
      if (pos_ >= s_.size()) fail("unclosed <" + e.name + ">");
      if (starts("<!--")) {
        skip_past("-->");
      } else if (starts("</")) {
        pos_ += 2;
        if (name() != e.name) fail("mismatched closing tag for <" + e.name + ">");
        skip_ws();
        if (!starts(">")) fail("expected '>'");
        ++pos_;
        return e;
      } else if (starts("<")) {
        e.children.push_back(element());
      } else {
        const auto next = s_.find('<', pos_);
        if (next == std::string::npos) fail("unclosed <" + e.name + ">");
        e.text += decode(s_.substr(pos_, next - pos_));
        pos_ = next;
      }
    }
  }

  std::string s_;
  std::size_t pos_ = 0;
};

Element parse_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return MiniXml(buffer.str()).parse();
}

std::string dims_text(const std::vector<hsize_t>& dims) {
  std::string out;
  for (const hsize_t d : dims) {
    if (!out.empty()) out += ' ';
    out += std::to_string(d);
  }
  return out;
}

/// Every Format="HDF" item below `e` must name run.h5 relatively and match the dataset's shape.
void expect_references_resolve(const Element& e, hid_t file, int* count) {
  for (const Element& child : e.children) {
    if (child.name == "DataItem" && child.attrs.count("Format") != 0 &&
        child.attr("Format") == "HDF") {
      const std::string ref = child.trimmed_text();
      SCOPED_TRACE(ref);
      ASSERT_EQ(ref.rfind("run.h5:/", 0), 0u);
      const std::string path = ref.substr(std::string("run.h5:").size());
      ASSERT_GT(H5Lexists(file, path.c_str(), H5P_DEFAULT), 0);
      EXPECT_EQ(child.attr("Dimensions"), dims_text(dataset_dims(file, path)));
      ++*count;
    }
    expect_references_resolve(child, file, count);
  }
}

const Element& temporal_collection(const Element& root) {
  EXPECT_EQ(root.name, "Xdmf");
  const Element& grid = root.one("Domain").one("Grid");
  EXPECT_EQ(grid.attr("GridType"), "Collection");
  EXPECT_EQ(grid.attr("CollectionType"), "Temporal");
  return grid;
}

TEST(RunFileXdmf, ListsEveryFrameWithTimeAndReferences) {
  const auto dir = scratch_dir("xdmf");
  const double times[3] = {0.0, 1e-3, 2.0 / 3.0};
  std::vector<double> xy(10), r(5), v(10);
  {
    RunFile run(dir, "scene", {});
    EXPECT_TRUE(temporal_collection(parse_file(dir / "run.xdmf")).all("Grid").empty());
    for (int f = 0; f < 3; ++f) {
      for (std::size_t i = 0; i < 10; ++i) xy[i] = v[i] = f + 0.5 * static_cast<double>(i);
      run.write_frame(times[f], static_cast<std::uint64_t>(f),
                      5, {{"position", 2, xy}, {"radius", 1, r}, {"velocity", 2, v}});
      // Rewritten after every frame, not only at close.
      EXPECT_EQ(temporal_collection(parse_file(dir / "run.xdmf")).all("Grid").size(),
                static_cast<std::size_t>(f + 1));
    }
  }
  const Element root = parse_file(dir / "run.xdmf");
  const auto grids = temporal_collection(root).all("Grid");
  ASSERT_EQ(grids.size(), 3u);
  for (int f = 0; f < 3; ++f) {
    const Element& g = *grids[static_cast<std::size_t>(f)];
    const std::string frame = "run.h5:/frames/00000" + std::to_string(f) + "/";
    SCOPED_TRACE(frame);
    EXPECT_EQ(g.attr("GridType"), "Uniform");
    EXPECT_EQ(std::strtod(g.one("Time").attr("Value").c_str(), nullptr), times[f]);
    const Element& topology = g.one("Topology");
    EXPECT_EQ(topology.attr("TopologyType"), "Polyvertex");
    EXPECT_EQ(topology.attr("NumberOfElements"), "5");
    const Element& geometry = g.one("Geometry");
    EXPECT_EQ(geometry.attr("GeometryType"), "XY");
    EXPECT_EQ(geometry.one("DataItem").trimmed_text(), frame + "position");
    EXPECT_EQ(geometry.one("DataItem").attr("Dimensions"), "5 2");
    std::map<std::string, const Element*> attributes;
    for (const Element* a : g.all("Attribute")) attributes[a->attr("Name")] = a;
    ASSERT_EQ(attributes.size(), 2u);
    EXPECT_EQ(attributes.at("radius")->attr("AttributeType"), "Scalar");
    EXPECT_EQ(attributes.at("radius")->attr("Center"), "Node");
    EXPECT_EQ(attributes.at("radius")->one("DataItem").trimmed_text(), frame + "radius");
    EXPECT_EQ(attributes.at("velocity")->attr("AttributeType"), "Vector");
    EXPECT_EQ(attributes.at("velocity")->one("DataItem").attr("Dimensions"), "5 2");
  }
  // After close the HDF5 file opens read-only and every reference in the XDMF resolves.
  h5::Handle file = open_read_only(dir / "run.h5");
  int references = 0;
  expect_references_resolve(root, file.get(), &references);
  EXPECT_EQ(references, 3 * 4);  // ids, position, radius, velocity per grid
  const std::vector<std::int32_t> ids = read_i32s(file.get(), "/xdmf/vertex_ids");
  EXPECT_EQ(ids, (std::vector<std::int32_t>{0, 1, 2, 3, 4}));

  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"run.h5", "run.xdmf"}));  // no temporaries left
}

TEST(RunFileXdmf, VaryingCountsSelectTheRightConnectivityAndSkipEmptyFrames) {
  const auto dir = scratch_dir("xdmf_counts");
  {
    RunFile run(dir, "scene", {});
    const std::vector<double> a(6, 1.0), b(14, 2.0);
    run.write_frame(0.0, 0, 3, {{"position", 2, a}});
    run.write_frame(1.0, 1, 0, {{"position", 2, {}}});
    run.write_frame(2.0, 2, 7, {{"position", 2, b}});
  }
  const Element root = parse_file(dir / "run.xdmf");
  const auto grids = temporal_collection(root).all("Grid");
  ASSERT_EQ(grids.size(), 2u);  // the empty frame has no datasets to point at
  EXPECT_EQ(grids[1]->one("Geometry").one("DataItem").trimmed_text(),
            "run.h5:/frames/000002/position");
  const std::string counts[2] = {"3", "7"};
  for (std::size_t i = 0; i < 2; ++i) {
    const Element& slab = grids[i]->one("Topology").one("DataItem");
    EXPECT_EQ(slab.attr("ItemType"), "HyperSlab");
    EXPECT_EQ(slab.attr("Dimensions"), counts[i]);
    const auto items = slab.all("DataItem");
    ASSERT_EQ(items.size(), 2u);
    EXPECT_EQ(items[0]->trimmed_text(), "0 1 " + counts[i]);  // start, stride, count
    EXPECT_EQ(items[1]->trimmed_text(), "run.h5:/xdmf/vertex_ids");
  }
  h5::Handle file = open_read_only(dir / "run.h5");
  int references = 0;
  expect_references_resolve(root, file.get(), &references);
  EXPECT_EQ(references, 4);
  EXPECT_EQ(read_i32s(file.get(), "/xdmf/vertex_ids"),
            (std::vector<std::int32_t>{0, 1, 2, 3, 4, 5, 6}));
}

}  // namespace
}  // namespace rockcut::coupler::testing
