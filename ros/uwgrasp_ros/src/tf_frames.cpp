#include "tf_frames.hpp"

#include "convert.hpp"

namespace uwgrasp_ros {

CaptureFrames capture_frames(const tf2::BufferCore& tf, const std_msgs::Header& h, const FrameNames& names,
                             const std::optional<std::array<double, 2>>& imu_roll_pitch) {
  if (h.frame_id.empty()) throw uwgrasp::Error("the cloud's header has no frame_id (its camera optical frame)");
  CaptureFrames c;
  c.capture.roll_pitch = imu_roll_pitch;
  if (!names.base.empty()) {
    c.capture.ros_body_from_camera = pose7(tf.lookupTransform(names.base, h.frame_id, h.stamp).transform);
    if (!c.capture.roll_pitch && !names.fixed.empty()) {
      const auto& r = tf.lookupTransform(names.fixed, names.base, h.stamp).transform.rotation;
      c.capture.roll_pitch = roll_pitch_from({r.x, r.y, r.z, r.w});
    }
  }
  if (!names.fixed.empty()) c.fixed_from_camera = pose7(tf.lookupTransform(names.fixed, h.frame_id, h.stamp).transform);
  return c;
}

}  // namespace uwgrasp_ros
