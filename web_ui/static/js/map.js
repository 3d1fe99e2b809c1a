// The live map: owns the canvas, redraws the latest state on every animation frame, pans on
// drag, zooms on the wheel, and turns a click into a fly command. It draws the world the
// simulator runs: the drone's arena, or the robot world's room (world.kind).

import { config } from "./config.js";
import { View } from "./geometry.js";
import {
  COLORS,
  drawArena,
  drawBoxes,
  drawCross,
  drawDrone,
  drawGrid,
  drawLayer,
  drawObstacles,
  drawPeople,
  drawRobot,
  drawRoom,
  drawScaleBar,
  drawScan,
  drawTour,
  drawTrack,
} from "./map_draw.js";

const CLICK_SLOP_PX = 4;
const ARENA = config.worlds.drone; // the core's numbers, not a copy
const ROOM = config.worlds.robot;
const STALE_POSE_S = 2;

export class MapView {
  /** `onClick(x, y)` receives map coordinates of a click (not a drag). */
  constructor(canvas, { world, room, layers, onClick, follow, cursorLabel }) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.world = world;
    this.room = room;
    this.layers = layers;
    this.onClick = onClick;
    this.follow = follow;
    this.cursorLabel = cursorLabel;
    this.view = new View();
    this.frames = 0;
    this._fitted = false;
    this._drag = null;
    new ResizeObserver(() => this._resize()).observe(canvas.parentElement);
    this._bindPointer();
    this._resize();
  }

  start() {
    const loop = () => {
      this.draw();
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  fit() {
    // The room with half a metre to spare, so the legend over the map's top hides no wall.
    this.view.fit(this.world.kind === "robot" ? ROOM.room_half_size_m + ROOM.wall_thickness_m + 0.5 : ARENA.fly_half_size_m);
  }

  /** Page (client) coordinates of a map point: where a test or a user would click. */
  worldToClient(x, y) {
    const rect = this.canvas.getBoundingClientRect();
    const [sx, sy] = this.view.toScreen(x, y);
    return { x: rect.left + sx, y: rect.top + sy };
  }

  clientToWorld(clientX, clientY) {
    const rect = this.canvas.getBoundingClientRect();
    const [x, y] = this.view.toWorld(clientX - rect.left, clientY - rect.top);
    return { x, y };
  }

  draw() {
    const { ctx, view, world } = this;
    const robot = world.kind === "robot";
    const pose = robot ? this.room.robots[0] && this.room.robots[0].pose : world.pose;
    if (this.follow.checked && pose) {
      view.cx = pose.x;
      view.cy = pose.y;
    }
    const dpr = window.devicePixelRatio || 1;
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = COLORS.background;
    ctx.fillRect(0, 0, view.width, view.height);
    drawGrid(ctx, view);
    if (robot) this._drawRoom();
    else this._drawArena(pose);
    for (const layer of this.layers.list()) drawLayer(ctx, view, layer);
    drawScaleBar(ctx, view);
    this.frames += 1;
  }

  /** The robot world: walls, obstacles, the person; per robot its odometry trail, scan, body. */
  _drawRoom() {
    const { ctx, view, room } = this;
    drawRoom(ctx, view, ROOM.room_half_size_m, ROOM.wall_thickness_m);
    drawObstacles(ctx, view, room.obstacles);
    drawPeople(ctx, view, room.people, ROOM.leg_radius_m, ROOM.leg_spacing_m);
    const stale = room.odomAgeSeconds() > STALE_POSE_S;
    for (const robot of room.robots) {
      drawTrack(ctx, view, robot.trail.map((p) => room.odomToMap(robot, p)), COLORS.odomTrail);
      if (!robot.pose) continue;
      if (robot.scan) drawScan(ctx, view, robot.pose, robot.scan.points);
      drawRobot(ctx, view, robot.pose, ROOM.robot_radius_m, robot.label, robot.bump, stale);
    }
  }

  /** The drone world: the fly area, boxes, the AI's tour, the track, setpoint and the drone. */
  _drawArena(pose) {
    const { ctx, view, world } = this;
    drawArena(ctx, view, ARENA.fly_half_size_m);
    drawBoxes(ctx, view, ARENA.box_size_m, world.simBoxes, world.perceptionBoxes, world.aiStatus);
    drawTour(ctx, view, pose, world.perceptionBoxes, world.aiStatus);
    drawTrack(ctx, view, world.track);
    const control = world.controlState;
    if (control && control.setpoint && control.state !== "landed") {
      drawCross(ctx, view, control.setpoint, COLORS.setpoint, "setpoint", "above");
    }
    if (world.flyTarget) drawCross(ctx, view, world.flyTarget, COLORS.flyTarget, "clicked", "below");
    if (pose) drawDrone(ctx, view, pose, world.poseAgeSeconds() > STALE_POSE_S);
  }

  _resize() {
    const rect = this.canvas.parentElement.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    this.canvas.width = Math.round(rect.width * dpr);
    this.canvas.height = Math.round(rect.height * dpr);
    this.canvas.style.width = `${rect.width}px`;
    this.canvas.style.height = `${rect.height}px`;
    this.view.resize(rect.width, rect.height);
    if (!this._fitted && rect.width > 10 && rect.height > 10) {
      this.fit();
      this._fitted = true;
    }
  }

  _bindPointer() {
    const canvas = this.canvas;
    canvas.addEventListener("pointerdown", (event) => {
      if (event.button !== 0) return;
      canvas.setPointerCapture(event.pointerId);
      this._drag = { x: event.clientX, y: event.clientY, moved: false };
    });
    canvas.addEventListener("pointermove", (event) => {
      const { x, y } = this.clientToWorld(event.clientX, event.clientY);
      this.cursorLabel.textContent = `x ${x.toFixed(2)}, y ${y.toFixed(2)}`;
      const drag = this._drag;
      if (!drag) return;
      const dx = event.clientX - drag.x;
      const dy = event.clientY - drag.y;
      if (!drag.moved && Math.hypot(dx, dy) < CLICK_SLOP_PX) return;
      drag.moved = true;
      this.follow.checked = false;
      this.view.panBy(dx, dy);
      drag.x = event.clientX;
      drag.y = event.clientY;
    });
    canvas.addEventListener("pointerup", (event) => {
      const drag = this._drag;
      this._drag = null;
      if (!drag || drag.moved) return;
      const { x, y } = this.clientToWorld(event.clientX, event.clientY);
      this.onClick(x, y);
    });
    canvas.addEventListener("pointercancel", () => {
      this._drag = null;
    });
    canvas.addEventListener(
      "wheel",
      (event) => {
        event.preventDefault();
        const rect = canvas.getBoundingClientRect();
        this.view.zoomAt(event.clientX - rect.left, event.clientY - rect.top, Math.exp(-event.deltaY * 0.0015));
      },
      { passive: false },
    );
  }
}
