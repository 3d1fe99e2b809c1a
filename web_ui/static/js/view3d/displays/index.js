// Which display draws which message type: the "add by topic" list offers every live topic whose
// type is here.

import { PathDisplay, PointDisplay, PolygonDisplay, PoseArrayDisplay, PoseDisplay } from "./geometry.js";
import { ImageDisplay } from "./image.js";
import { LaserScanDisplay } from "./laser_scan.js";
import { MarkerDisplay } from "./markers.js";
import { OdometryDisplay } from "./odometry.js";
import { TfDisplay } from "./tf.js";

export const DISPLAY_TYPES = new Map([
  ["geometry_msgs/msg/PointStamped", PointDisplay],
  ["geometry_msgs/msg/PoseStamped", PoseDisplay],
  ["geometry_msgs/msg/PoseArray", PoseArrayDisplay],
  ["geometry_msgs/msg/Polygon", PolygonDisplay],
  ["geometry_msgs/msg/PolygonStamped", PolygonDisplay],
  ["nav_msgs/msg/Path", PathDisplay],
  ["nav_msgs/msg/Odometry", OdometryDisplay],
  ["sensor_msgs/msg/LaserScan", LaserScanDisplay],
  ["visualization_msgs/msg/Marker", MarkerDisplay],
  ["visualization_msgs/msg/MarkerArray", MarkerDisplay],
  ["tf2_msgs/msg/TFMessage", TfDisplay],
  ["sensor_msgs/msg/Image", ImageDisplay],
  ["sensor_msgs/msg/CompressedImage", ImageDisplay],
]);

export function hasDisplay(type) {
  return DISPLAY_TYPES.has(type);
}

/** A new display of `type` on `topic`; null when no display draws that type. */
export function createDisplay(topic, type, settings, env) {
  const Kind = DISPLAY_TYPES.get(type);
  return Kind ? new Kind(topic, type, settings, env) : null;
}
