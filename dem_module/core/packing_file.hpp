// A disc packing as a plain text file, so a specimen can be generated once (or elsewhere) and reused.
//
// Format: one disc per line, "x_m y_m radius_m [vx_m_s vy_m_s [omega_rad_s]]" (SI units,
// whitespace separated, any number format std::from_chars accepts, e.g. 1.5e-3): 3, 5 or 6
// numbers, the optional ones the disc's initial velocity and spin (0 where a line leaves them
// out), so a two-disc collision or a projectile is a packing file. Blank lines and everything
// after '#' are ignored. write_packing_file writes 17 significant digits (and the motion columns
// only when the packing has them), so a write/read round trip is bit-exact.
#pragma once

#include <filesystem>

#include "core/specimen_generator.hpp"

namespace rockcut::dem {

/// Throws std::runtime_error "<path>:<line>: <reason>" for an unreadable file, a malformed line
/// (not 3, 5 or 6 numbers), a non-finite value or a non-positive radius. The motion columns are
/// filled (zeros where a line has none) when any line gives them, else left empty.
Packing read_packing_file(const std::filesystem::path& path);

/// The same discs renumbered in row-major cell order (rows of cells one largest diameter high in
/// y, cells as wide in x within a row; file order within a cell), the order generate_packing gives. Neighbours then sit
/// close in memory, and with OpenMP each thread's share of the pairs touches mostly its own share
/// of the discs: on this machine a random order costs 1.8x in cache misses, and in two-thread
/// runs the second core pulls the first one's force lines across.
Packing in_cell_order(const Packing& packing);

/// Throws std::runtime_error naming the path if it cannot be written.
void write_packing_file(const std::filesystem::path& path, const Packing& packing);

}  // namespace rockcut::dem
