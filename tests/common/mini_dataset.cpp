#include "common/mini_dataset.h"

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <sstream>

namespace edgevio::test {

std::string eurocCameraYaml(int cam, int width, int height) {
  const double s = width / 752.0;
  std::ostringstream o;
  o << "%YAML:1.0\n"
    << "sensor_type: camera\ncomment: test cam" << cam << "\n"
    << "T_BS:\n  cols: 4\n  rows: 4\n"
    << (cam == 0 ? "  data: [0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975,\n"
                   "         0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768,\n"
                   "        -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949,\n"
                   "         0.0, 0.0, 0.0, 1.0]\n"
                 : "  data: [0.0125552670891, -0.999755099723, 0.0182237714554, -0.0198435579556,\n"
                   "         0.999598781151, 0.0130119051815, 0.0251588363115, 0.0453689425024,\n"
                   "        -0.0253898008918, 0.0179005838253, 0.999517347078, 0.00786212447038,\n"
                   "         0.0, 0.0, 0.0, 1.0]\n")
    << "rate_hz: 20\n"
    << "resolution: [" << width << ", " << height << "]\n"
    << "camera_model: pinhole\n"
    << "intrinsics: [" << 458.654 * s << ", " << 457.296 * s << ", " << 367.215 * s << ", " << 248.375 * s
    << "]\n"
    << "distortion_model: radial-tangential\n"
    << "distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]\n";
  return o.str();
}

std::string eurocImuYaml() {
  return "%YAML:1.0\nsensor_type: imu\nT_BS:\n  cols: 4\n  rows: 4\n"
         "  data: [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]\n"
         "rate_hz: 200\n"
         "gyroscope_noise_density: 1.6968e-04\n"
         "gyroscope_random_walk: 1.9393e-05\n"
         "accelerometer_noise_density: 2.0000e-3\n"
         "accelerometer_random_walk: 3.0000e-3\n";
}

std::string writeMiniDataset(const TempDir& dir, const MiniDatasetSpec& spec) {
  namespace fs = std::filesystem;
  const fs::path mav0 = fs::path(dir.path()) / "mav0";
  for (int cam = 0; cam < 2; ++cam) {
    const fs::path c = mav0 / ("cam" + std::to_string(cam));
    fs::create_directories(c / "data");
    std::ostringstream csv;
    csv << "#timestamp [ns],filename\n";
    for (int i = 0; i < spec.frames; ++i) {
      const std::int64_t t = spec.t0_ns + i * spec.frame_dt_ns;
      cv::Mat img(spec.height, spec.width, CV_8UC1, cv::Scalar(40 + 10 * i + 5 * cam));
      if (spec.patterned)
        for (int y = 0; y < spec.height; ++y)
          for (int x = 0; x < spec.width; ++x) img.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(7 * x + 13 * y + 10 * i + 5 * cam);
      cv::imwrite((c / "data" / (std::to_string(t) + ".png")).string(), img);
      csv << t << "," << t << ".png\n";
    }
    dir.write("mav0/cam" + std::to_string(cam) + "/data.csv", csv.str());
    dir.write("mav0/cam" + std::to_string(cam) + "/sensor.yaml", eurocCameraYaml(cam, spec.width, spec.height));
  }
  std::ostringstream imu;
  imu << "#timestamp [ns],w_x,w_y,w_z,a_x,a_y,a_z\n";
  const std::int64_t t_end = spec.t0_ns + (spec.frames - 1) * spec.frame_dt_ns;
  for (std::int64_t t = spec.t0_ns - 10 * spec.imu_dt_ns; t <= t_end + 10 * spec.imu_dt_ns; t += spec.imu_dt_ns)
    imu << t << ",0.001,-0.002,0.003,0.1,0.2,9.81\n";
  dir.write("mav0/imu0/data.csv", imu.str());
  dir.write("mav0/imu0/sensor.yaml", eurocImuYaml());
  std::ostringstream gt;
  gt << "#timestamp,p_x,p_y,p_z,q_w,q_x,q_y,q_z,v_x,v_y,v_z,bw_x,bw_y,bw_z,ba_x,ba_y,ba_z\n";
  for (int i = 0; i < spec.frames; ++i)
    gt << spec.t0_ns + i * spec.frame_dt_ns << "," << 0.1 * i << ",0,1,1,0,0,0,2,0,0,0.001,0,0,0,0,0.01\n";
  dir.write("mav0/state_groundtruth_estimate0/data.csv", gt.str());
  return dir.path();
}

}  // namespace edgevio::test
