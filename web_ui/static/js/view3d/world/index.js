// The simulator's world as the 3D view's first, built-in display ("World"): the drone world
// and the robot world, each drawn once its topics or frames appear. It can be hidden, not removed.

import * as THREE from "three";
import { BadData } from "../ros_math.js";
import { StatusList } from "../status_list.js";
import { DroneWorld } from "./drone_world.js";
import { RobotWorld } from "./robot_world.js";

export class SimWorld {
  constructor(worlds, tf) {
    this.label = "World";
    this.visible = true;
    this.statuses = new StatusList();
    this.root = new THREE.Group();
    this.drone = worlds.drone ? new DroneWorld(worlds.drone, tf) : null;
    this.robot = new RobotWorld(worlds.robot, tf, { tf });
    if (this.drone) this.root.add(this.drone.root);
    this.root.add(this.robot.root);
    this.statuses.set("World", "warn", "no simulator topics yet (/drone/pose, /simulator/boxes, /simulator/obstacles, base_link in TF)");
    this._roomVersion = -1;
  }

  start() {
    this.drone?.start();
    this.robot.start();
  }

  stop() {
    this.drone?.stop();
    this.robot.stop();
  }

  update(ctx) {
    let changed = false;
    const drone = this.drone;
    if (drone) {
      let fresh = false;
      try {
        fresh = drone.update(ctx);
        this.statuses.clear("Drone data");
      } catch (error) {
        if (!(error instanceof BadData)) throw error;
        this.statuses.set("Drone data", "error", `skipped: ${error.message}`);
      }
      if (drone.present && (fresh || ctx.tfChanged || ctx.fixedFrameChanged || ctx.tfStructureChanged)) {
        const found = ctx.lookup(drone.frame, null, drone.root.matrix);
        drone.root.visible = !found.error;
        drone.root.matrixWorldNeedsUpdate = true;
        if (found.error) this.statuses.set("Drone world", "error", found.error);
        else this.statuses.set("Drone world", "ok", `in frame ${drone.frame}`);
        changed = true;
      }
    }
    try {
      changed = this.robot.update(ctx) || changed;
      this.statuses.clear("Room data");
    } catch (error) {
      if (!(error instanceof BadData)) throw error;
      this.statuses.set("Room data", "error", `skipped: ${error.message}`);
    }
    this._roomStatus();
    if ((drone && drone.present) || this.robot.present) this.statuses.clear("World");
    return changed;
  }

  /** The room's markers as one line of the World's status: the worst of their entries. */
  _roomStatus() {
    const room = this.robot.obstacles;
    if (room.statuses.version === this._roomVersion) return;
    this._roomVersion = room.statuses.version;
    if (!room.received) return;
    const { level, entries } = room.status();
    const worst = entries.find((e) => e.level === level && e.key !== "Topic");
    this.statuses.set("Room", level, level === "ok" || !worst ? "walls and boxes of /simulator/obstacles" : `${worst.key}: ${worst.text}`);
  }

  setVisible(visible) {
    this.visible = visible;
    this.root.visible = visible;
  }

  status() {
    return this.statuses.summary();
  }

  /** The robot (or drone) in the fixed frame, for the follow view; null when neither is drawn. */
  followPoint() {
    return this.robot.followPoint() || (this.drone && this.drone.present ? this.drone.followPoint() : null);
  }

  /** Half the size of the world shown, in metres (grid and the top-down view). */
  extent() {
    if (this.robot.present || !this.drone) return this.robot.extent();
    return this.drone.extent();
  }

  /** Which world the simulator runs, once its topics or frames say so: "robot", "drone" or null. */
  kind() {
    if (this.robot.present) return "robot";
    return this.drone && this.drone.present ? "drone" : null;
  }

  /** What the view frames (a THREE.Box3 in the world's frame, `map`), for kind(). */
  bounds() {
    return this.kind() === "drone" ? this.drone.bounds() : this.robot.bounds();
  }

  /** How close Follow brings the camera, in metres. */
  followDistance() {
    return this.kind() === "drone" ? this.drone.followDistance() : this.robot.followDistance();
  }

  /** Draw the drone and the robots at least `minPx` across (`pixelsPerMetre(point)`: the view's
   * scale at a point); true if a model's size changed. */
  fitModels(pixelsPerMetre, minPx) {
    if (!this.visible) return false;
    const drone = this.drone ? this.drone.fitModel(pixelsPerMetre, minPx) : false;
    return this.robot.fitModels(pixelsPerMetre, minPx) || drone;
  }

  snapshot() {
    return {
      visible: this.visible,
      kind: this.kind(),
      status: this.status(),
      drone: this.drone ? this.drone.snapshot() : null,
      robot: this.robot.snapshot(),
    };
  }
}
