#include "io/vtu_binary.hpp"

#include "io/zlib_blocks.hpp"

namespace tem {
namespace {

static_assert(sizeof(int) == 4, "ints are written as Int32");
static_assert(sizeof(Real) == 8, "Reals are written as Float64");

const std::string kThreeComponents = " NumberOfComponents=\"3\"";

}  // namespace

VtuBinary::VtuBinary(Real time, size_t points, size_t cells) {
  xml_ =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
      "<UnstructuredGrid>\n"
      "<FieldData>\n";
  scratch_.assign(1, time + 0.0);
  scratch_array("TimeValue", " NumberOfTuples=\"1\"");
  xml_ += "</FieldData>\n<Piece NumberOfPoints=\"" + std::to_string(points) +
          "\" NumberOfCells=\"" + std::to_string(cells) + "\">\n";
}

void VtuBinary::array(const char* type, const char* name, const std::string& extra,
                      const void* bytes, size_t size) {
  xml_ += "<DataArray type=\"";
  xml_ += type;
  xml_ += "\" Name=\"";
  xml_ += name;
  xml_ += '"';
  // Scalars go without NumberOfComponents, as VTK writes them: readers then give 1-D arrays.
  xml_ += extra;
  xml_ += " format=\"appended\" offset=\"";
  offset_at_.push_back(xml_.size());  // the offset goes here once the layout is known (finish)
  xml_ += "\"/>\n";
  chunk_start_.push_back(data_.size());
  append_zlib_blocks(data_, bytes, size);
}

void VtuBinary::scratch_array(const char* name, const std::string& extra) {
  array("Float64", name, extra, scratch_.data(), scratch_.size() * sizeof(Real));
}

// Adding +0.0 turns -0 into 0 and leaves every other double as it is.
void VtuBinary::fill_scratch(const std::vector<Vec3>& values) {
  scratch_.resize(3 * values.size());
  Real* out = scratch_.data();
  for (const Vec3& v : values)
    for (int k = 0; k < 3; ++k) *out++ = v[k] + 0.0;
}

void VtuBinary::vectors(const char* name, const std::vector<Vec3>& values) {
  fill_scratch(values);
  scratch_array(name, kThreeComponents);
}

void VtuBinary::reals(const char* name, const std::vector<Real>& values) {
  scratch_.resize(values.size());
  for (size_t i = 0; i < values.size(); ++i) scratch_[i] = values[i] + 0.0;
  scratch_array(name, "");
}

void VtuBinary::ints(const char* name, const std::vector<int>& values) {
  array("Int32", name, "", values.data(), values.size() * sizeof(int));
}

void VtuBinary::points(const std::vector<Vec3>& positions) {
  xml_ += "<Points>\n";
  fill_scratch(positions);
  scratch_array("Points", kThreeComponents);
  xml_ += "</Points>\n";
}

void VtuBinary::cells(const std::vector<std::int64_t>& connectivity, int nodes_per_cell,
                      std::uint8_t type) {
  const size_t count = connectivity.size() / static_cast<size_t>(nodes_per_cell);
  xml_ += "<Cells>\n";
  array("Int64", "connectivity", "", connectivity.data(),
        connectivity.size() * sizeof(std::int64_t));
  std::vector<std::int64_t> offsets(count);
  for (size_t c = 0; c < count; ++c) offsets[c] = static_cast<std::int64_t>(c + 1) * nodes_per_cell;
  array("Int64", "offsets", "", offsets.data(), offsets.size() * sizeof(std::int64_t));
  const std::vector<std::uint8_t> types(count, type);
  array("UInt8", "types", "", types.data(), types.size());
  xml_ += "</Cells>\n";
}

std::string VtuBinary::finish() {
  // The arrays' bytes go in the reverse of their XML order (vtu_binary.hpp says why): the last
  // array declared at offset 0, the first one last.
  const size_t n = chunk_start_.size();
  auto chunk_end = [&](size_t k) { return k + 1 < n ? chunk_start_[k + 1] : data_.size(); };
  std::vector<size_t> offset(n);
  size_t next = 0;
  for (size_t k = n; k-- > 0;) {
    offset[k] = next;
    next += chunk_end(k) - chunk_start_[k];
  }
  std::string out;
  out.reserve(xml_.size() + data_.size() + 20 * n + 128);
  size_t copied = 0;
  for (size_t k = 0; k < n; ++k) {
    out.append(xml_, copied, offset_at_[k] - copied);
    out += std::to_string(offset[k]);
    copied = offset_at_[k];
  }
  out.append(xml_, copied, std::string::npos);
  // The raw data starts after the underscore and ends before the newline (VTK's layout; meshio
  // relies on both).
  out += "</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  for (size_t k = n; k-- > 0;) out.append(data_, chunk_start_[k], chunk_end(k) - chunk_start_[k]);
  out += "\n</AppendedData>\n</VTKFile>\n";
  xml_.clear();
  data_.clear();
  offset_at_.clear();
  chunk_start_.clear();
  return out;
}

}  // namespace tem
