#pragma once
// A whole IMU record parsed into memory once and shared, read-only, by every run that navigates
// on it (the variants of one seed in `stochnav compare`), instead of each run parsing the file.
// Memory: sizeof(ImuIncrement) (64 bytes) per epoch.

#include <memory>
#include <string>
#include <vector>

#include "stochnav/ins/strapdown.hpp"

namespace stochnav {

struct ImuRecord {
  std::string path;                  ///< the file it was read from
  double rate_hz = 0.0;              ///< nominal rate from the first interval (Hz)
  double start_time_s = 0.0;         ///< start of the first interval (s)
  std::vector<ImuIncrement> epochs;  ///< every epoch's increments (rad, m/s; body frame)
};

/// Reads the whole file with ImuFileReader (experiment/navigation_files.hpp: same columns,
/// units and checks). Throws InputError "file:line: ..." for the first bad row.
std::shared_ptr<const ImuRecord> read_imu_record(const std::string& path);

}  // namespace stochnav
