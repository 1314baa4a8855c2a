// The text of a VTK XML UnstructuredGrid file (.vtu), ASCII, built in one std::string so that a
// frame is written with a single write. ASCII rather than base64 binary because it is what
// Debian's meshio and a text editor can both read; numbers carry the shortest digits that read
// back as the same double (csv_number.hpp), so nothing is lost.
//
// The XML order is the one VTK writes: the Piece's PointData, CellData, Points, then Cells.
// Call the member functions in that order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tem/types.hpp"

namespace tem {

// VTK cell type numbers (vtkCellType.h).
inline constexpr std::uint8_t kVtkVertex = 1;
inline constexpr std::uint8_t kVtkTriangle = 5;

class VtuText {
 public:
  // Opens the file, with `time` as the FieldData array TimeValue (ParaView's name for it).
  VtuText(Real time, size_t points, size_t cells);

  void begin_point_data() { text_ += "<PointData>\n"; }
  void end_point_data() { text_ += "</PointData>\n"; }
  void begin_cell_data() { text_ += "<CellData>\n"; }
  void end_cell_data() { text_ += "</CellData>\n"; }

  void vectors(const char* name, const std::vector<Vec3>& values);  // Float64, 3 components
  void reals(const char* name, const std::vector<Real>& values);    // Float64
  void ints(const char* name, const std::vector<int>& values);      // Int32

  void points(const std::vector<Vec3>& positions);
  // Cells of one type with `nodes_per_cell` point indices each, listed one cell after another.
  void cells(const std::vector<std::int64_t>& connectivity, int nodes_per_cell, std::uint8_t type);

  // Closes the file and hands over its text.
  std::string finish();

 private:
  std::string text_;
};

}  // namespace tem
