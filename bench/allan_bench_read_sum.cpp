// The physical limit of a whole-process Allan run on a raw float64 file: start, map the file,
// read every sample once (a sum, so nothing is optimised away), print, exit.
// Usage: allan_bench_read_sum FILE.f64

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const int fd = ::open(argv[1], O_RDONLY);
  struct stat status {};
  if (fd < 0 || ::fstat(fd, &status) != 0) return 2;
  const auto bytes = static_cast<std::size_t>(status.st_size);
  void* map = ::mmap(nullptr, bytes, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
  if (map == MAP_FAILED) return 2;
  const auto* x = static_cast<const double*>(map);
  const std::size_t n = bytes / sizeof(double);
  std::array<double, 8> lanes{};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    for (std::size_t lane = 0; lane < 8; ++lane) lanes[lane] += x[i + lane];
  }
  for (; i < n; ++i) lanes[0] += x[i];
  double sum = 0.0;
  for (double lane : lanes) sum += lane;
  std::printf("{\"samples\": %zu, \"sum\": %.17g}\n", n, sum);
  return 0;
}
