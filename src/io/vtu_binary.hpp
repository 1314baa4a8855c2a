// A VTK XML UnstructuredGrid file (.vtu) in VTK's binary form: the XML declares each array
// (format="appended" with its byte offset), and after the XML, in <AppendedData encoding="raw">,
// every array's bytes follow one another, compressed with zlib in VTK's blocks (zlib_blocks.hpp).
// Binary because of size and speed at scale: a frame of 100,000 coins was 432 MB of text that
// took about 2 s to write, and is 123 MB written in about 1 s (docs/benchmarks.md, "ParaView
// output at scale"); a double is stored in its 8 bytes, exactly, with nothing to format or parse.
// Debian's meshio and ParaView read it; tests/support/vtu_reader.hpp decodes it for the tests.
//
// Values are stored as the ASCII files had them: -0 is written as 0 (the ASCII files never held
// "-0", csv_number.hpp), every other double bit for bit.
//
// The XML order is the one VTK writes: the Piece's PointData, CellData, Points, then Cells.
// Call the member functions in that order. The arrays' bytes are appended in the reverse of
// that order, the last array declared first. Why: Debian's meshio reads raw appended data by
// rewriting each array's offset into one of its own and looking the next array up by its raw
// offset, first match in XML order; laid out in XML order, an array already rewritten could
// carry the very offset of one still to come and be read in its place (a contacts frame of 52
// points failed so: tests/paraview/check_paraview.py). Laid out in reverse, the array looked
// up always comes before every rewritten one. ParaView reads either layout. The whole file is
// built in memory, so a frame is
// written with a single write.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tem/types.hpp"

namespace tem {

// VTK cell type numbers (vtkCellType.h).
inline constexpr std::uint8_t kVtkVertex = 1;
inline constexpr std::uint8_t kVtkTriangle = 5;

class VtuBinary {
 public:
  // Opens the file, with `time` as the FieldData array TimeValue (ParaView's name for it).
  VtuBinary(Real time, size_t points, size_t cells);

  void begin_point_data() { xml_ += "<PointData>\n"; }
  void end_point_data() { xml_ += "</PointData>\n"; }
  void begin_cell_data() { xml_ += "<CellData>\n"; }
  void end_cell_data() { xml_ += "</CellData>\n"; }

  void vectors(const char* name, const std::vector<Vec3>& values);  // Float64, 3 components
  void reals(const char* name, const std::vector<Real>& values);    // Float64
  void ints(const char* name, const std::vector<int>& values);      // Int32

  void points(const std::vector<Vec3>& positions);
  // Cells of one type with `nodes_per_cell` point indices each, listed one cell after another.
  void cells(const std::vector<std::int64_t>& connectivity, int nodes_per_cell, std::uint8_t type);

  // Closes the file and hands over its bytes.
  std::string finish();

 private:
  // Declares the array in the XML at the current end of the appended data, then appends it.
  // `extra` goes into the tag as it is (NumberOfComponents, NumberOfTuples).
  void array(const char* type, const char* name, const std::string& extra, const void* bytes,
             size_t size);
  // A Float64 array of the values in scratch_ (where -0 was made 0).
  void scratch_array(const char* name, const std::string& extra);
  void fill_scratch(const std::vector<Vec3>& values);

  std::string xml_;            // the XML up to the end of the Piece, without the offsets
  std::string data_;           // every array's header and zlib blocks, in XML order
  std::vector<size_t> offset_at_;    // per array: where in xml_ its offset goes
  std::vector<size_t> chunk_start_;  // per array: where in data_ its bytes start
  std::vector<Real> scratch_;  // Float64 values on their way into data_
};

}  // namespace tem
