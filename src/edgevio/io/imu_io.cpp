#include "edgevio/io/imu_io.h"

#include <cmath>
#include <cstdio>
#include <memory>

#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/table_reader.h"
#include "edgevio/common/time.h"

namespace edgevio::io {

std::vector<imu::ImuSample> readImuCsv(const std::string& path, double gap_warning_s, std::vector<std::string>* warnings) {
  TableReader r(path, TableReader::Separator::kComma);
  const auto gap_ns = toNanoseconds(gap_warning_s);
  std::vector<imu::ImuSample> imu;
  while (r.next()) {
    r.requireFields(7, "timestamp [ns],w_x,w_y,w_z,a_x,a_y,a_z");
    imu::ImuSample s;
    s.t_ns = r.integer(0);
    s.gyro = Vec3(r.number(1), r.number(2), r.number(3));
    s.accel = Vec3(r.number(4), r.number(5), r.number(6));
    if (!imu.empty()) {
      const std::int64_t dt = s.t_ns - imu.back().t_ns;
      if (dt <= 0)
        r.fail(std::string(dt == 0 ? "duplicate" : "decreasing") +
               " timestamp: IMU rows must be in strictly increasing time order");
      if (dt > gap_ns && warnings) {
        warnings->push_back(r.path() + ":" + std::to_string(r.line()) +
                            formatText(": IMU gap of %.3f s before t = %.3f s", toSeconds(dt), toSeconds(s.t_ns)));
      }
    }
    imu.push_back(s);
  }
  if (imu.size() < 2) throw InputError(path, 0, "fewer than 2 IMU samples");
  return imu;
}

void writeImuCsv(const std::string& path, const std::vector<imu::ImuSample>& samples) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) throw InputError(path, 0, "cannot open file for writing");
  std::fprintf(f.get(), "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
                        "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n");
  for (const auto& s : samples)
    std::fprintf(f.get(), "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", static_cast<long long>(s.t_ns), s.gyro.x(),
                 s.gyro.y(), s.gyro.z(), s.accel.x(), s.accel.y(), s.accel.z());
}

}  // namespace edgevio::io
