// Drawing the top-down map on a 2D canvas context: grid, boxes, tour, track, drone, layers; and
// for the robot world the room, its obstacles, the person, robots, scans and odometry trails.
// Pure functions of (ctx, view, data); map.js owns the canvas and calls them every frame.

export const COLORS = {
  background: "#0e1319",
  grid: "#18212b",
  gridMajor: "#243140",
  label: "#6f8193",
  axisX: "#e06c75",
  axisY: "#98c379",
  drone: "#61afef",
  track: "rgba(97, 175, 239, 0.55)",
  box: "#a98552",
  boxVisited: "#4caf50",
  boxTarget: "#ffb74d",
  tour: "#ffb74d",
  setpoint: "#c678dd",
  flyTarget: "#e5e5e5",
  text: "#d7dde3",
  wall: "#9aa7b4",
  obstacle: "#a98552",
  person: "#e06c75",
  robot: "#61afef",
  bump: "#ff5252",
  scan: "#98c379",
  odomTrail: "rgba(229, 192, 123, 0.75)",
};

export function drawGrid(ctx, view) {
  const [x0, y1] = view.toWorld(0, 0);
  const [x1, y0] = view.toWorld(view.width, view.height);
  const step = view.scale >= 8 ? 1 : 5; // metres between minor lines
  const major = view.scale >= 3 ? 5 : 10;
  ctx.lineWidth = 1;
  for (let x = Math.floor(x0 / step) * step; x <= x1; x += step) {
    const [sx] = view.toScreen(x, 0);
    ctx.strokeStyle = x % major === 0 ? COLORS.gridMajor : COLORS.grid;
    line(ctx, Math.round(sx) + 0.5, 0, Math.round(sx) + 0.5, view.height);
  }
  for (let y = Math.floor(y0 / step) * step; y <= y1; y += step) {
    const [, sy] = view.toScreen(0, y);
    ctx.strokeStyle = y % major === 0 ? COLORS.gridMajor : COLORS.grid;
    line(ctx, 0, Math.round(sy) + 0.5, view.width, Math.round(sy) + 0.5);
  }
  // Axes through the origin, labelled in metres along the edges.
  const [ox, oy] = view.toScreen(0, 0);
  ctx.strokeStyle = COLORS.axisX;
  line(ctx, ox, oy, view.width, oy);
  ctx.strokeStyle = COLORS.axisY;
  line(ctx, ox, oy, ox, 0);
  ctx.fillStyle = COLORS.label;
  ctx.font = "11px ui-monospace, monospace";
  ctx.textAlign = "center";
  ctx.textBaseline = "bottom";
  for (let x = Math.ceil(x0 / major) * major; x <= x1; x += major) {
    ctx.fillText(`${x}`, view.toScreen(x, 0)[0], view.height - 3);
  }
  ctx.textAlign = "left";
  ctx.textBaseline = "middle";
  for (let y = Math.ceil(y0 / major) * major; y <= y1; y += major) {
    if (Math.abs(view.toScreen(0, y)[1] - view.height) < 14) continue;
    ctx.fillText(`${y}`, 4, view.toScreen(0, y)[1]);
  }
  ctx.fillStyle = COLORS.axisX;
  ctx.textAlign = "right";
  ctx.fillText("x (m)", view.width - 6, Math.min(Math.max(oy - 10, 10), view.height - 24));
  ctx.fillStyle = COLORS.axisY;
  ctx.textAlign = "left";
  ctx.fillText("y (m)", Math.min(Math.max(ox + 6, 28), view.width - 40), 10);
}

/** The square control accepts fly targets in (±half m), dashed. */
export function drawArena(ctx, view, half) {
  const [x0, y0] = view.toScreen(-half, half);
  const [x1, y1] = view.toScreen(half, -half);
  ctx.save();
  ctx.setLineDash([4, 6]);
  ctx.strokeStyle = "#3b4b5c";
  ctx.lineWidth = 1;
  ctx.strokeRect(x0, y0, x1 - x0, y1 - y0);
  ctx.restore();
}

/** Index of the perception box nearest to (x, y) within 2 m, or -1. */
function nearestIndex(points, x, y) {
  let best = -1;
  let bestDistance = 2;
  points.forEach((p, i) => {
    const d = Math.hypot(p.x - x, p.y - y);
    if (d < bestDistance) {
      best = i;
      bestDistance = d;
    }
  });
  return best;
}

function boxColor(index, status) {
  if (index < 0 || !status) return COLORS.box;
  if ((status.visited || []).includes(index)) return COLORS.boxVisited;
  if (status.target === index) return COLORS.boxTarget;
  return COLORS.box;
}

/** The boxes: the simulator's (with their yaw) coloured by the AI's progress on perception's. */
export function drawBoxes(ctx, view, boxSize, simBoxes, perceptionBoxes, status) {
  const boxes = simBoxes.length
    ? simBoxes.map((b) => ({ ...b, index: nearestIndex(perceptionBoxes, b.x, b.y) }))
    : perceptionBoxes.map((p, index) => ({ x: p.x, y: p.y, yaw: 0, index }));
  const half = (boxSize / 2) * view.scale;
  for (const box of boxes) {
    const [sx, sy] = view.toScreen(box.x, box.y);
    const color = boxColor(box.index, status);
    ctx.save();
    ctx.translate(sx, sy);
    ctx.rotate(-box.yaw);
    ctx.fillStyle = `${color}55`;
    ctx.strokeStyle = color;
    ctx.lineWidth = 1.5;
    ctx.fillRect(-half, -half, 2 * half, 2 * half);
    ctx.strokeRect(-half, -half, 2 * half, 2 * half);
    ctx.restore();
    if (box.index >= 0) {
      const visited = status && (status.visited || []).includes(box.index);
      ctx.fillStyle = COLORS.text;
      ctx.font = "bold 12px system-ui, sans-serif";
      ctx.textAlign = "center";
      ctx.textBaseline = "middle";
      ctx.fillText(visited ? `✓${box.index}` : `${box.index}`, sx, sy);
    }
  }
}

/** The AI's planned tour: from the drone through the remaining boxes in order. */
export function drawTour(ctx, view, pose, perceptionBoxes, status) {
  if (!status || !Array.isArray(status.tour)) return;
  const order = [...status.tour];
  if (status.target >= 0 && order[0] !== status.target) order.unshift(status.target);
  const points = order.map((i) => perceptionBoxes[i]).filter(Boolean);
  if (!points.length) return;
  if (pose) points.unshift(pose);
  ctx.save();
  ctx.setLineDash([6, 5]);
  ctx.strokeStyle = COLORS.tour;
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  points.forEach((p, i) => {
    const [sx, sy] = view.toScreen(p.x, p.y);
    if (i === 0) ctx.moveTo(sx, sy);
    else ctx.lineTo(sx, sy);
  });
  ctx.stroke();
  ctx.restore();
}

export function drawTrack(ctx, view, track, color = COLORS.track) {
  if (track.length < 2) return;
  ctx.strokeStyle = color;
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  track.forEach((p, i) => {
    const [sx, sy] = view.toScreen(p.x, p.y);
    if (i === 0) ctx.moveTo(sx, sy);
    else ctx.lineTo(sx, sy);
  });
  ctx.stroke();
}

export function drawCross(ctx, view, point, color, label, where = "above") {
  const [sx, sy] = view.toScreen(point.x, point.y);
  ctx.strokeStyle = color;
  ctx.lineWidth = 1.5;
  line(ctx, sx - 7, sy - 7, sx + 7, sy + 7);
  line(ctx, sx - 7, sy + 7, sx + 7, sy - 7);
  if (label) {
    ctx.fillStyle = color;
    ctx.font = "11px system-ui, sans-serif";
    const above = where === "above";
    ctx.textAlign = above ? "left" : "right";
    ctx.textBaseline = above ? "bottom" : "top";
    ctx.fillText(label, above ? sx + 9 : sx - 9, above ? sy - 4 : sy + 4);
  }
}

/** The drone: a disc at its size (at least a few pixels), a heading arrow, its altitude. */
export function drawDrone(ctx, view, pose, stale) {
  const [sx, sy] = view.toScreen(pose.x, pose.y);
  const radius = Math.max(7, 0.35 * view.scale);
  const color = stale ? "#7d8895" : COLORS.drone;
  ctx.fillStyle = `${color}40`;
  ctx.strokeStyle = color;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.arc(sx, sy, radius, 0, 2 * Math.PI);
  ctx.fill();
  ctx.stroke();
  const length = radius + 12;
  const hx = sx + Math.cos(pose.yaw) * length;
  const hy = sy - Math.sin(pose.yaw) * length;
  line(ctx, sx, sy, hx, hy);
  const back = 7;
  ctx.beginPath();
  ctx.moveTo(hx, hy);
  ctx.lineTo(hx - Math.cos(pose.yaw - 0.45) * back, hy + Math.sin(pose.yaw - 0.45) * back);
  ctx.lineTo(hx - Math.cos(pose.yaw + 0.45) * back, hy + Math.sin(pose.yaw + 0.45) * back);
  ctx.closePath();
  ctx.fillStyle = color;
  ctx.fill();
  ctx.font = "bold 12px system-ui, sans-serif";
  ctx.textAlign = "left";
  ctx.textBaseline = "top";
  const text = `z ${pose.z.toFixed(2)} m`;
  ctx.fillStyle = "rgba(14, 19, 25, 0.8)";
  ctx.fillRect(sx + radius + 4, sy + 4, ctx.measureText(text).width + 8, 17);
  ctx.fillStyle = COLORS.text;
  ctx.fillText(text, sx + radius + 8, sy + 6);
}

/** A user layer (add by topic): its points, arrows for poses, an outline for polygons. */
export function drawLayer(ctx, view, layer) {
  const { color, points } = layer;
  if (!points.length) return;
  ctx.strokeStyle = color;
  ctx.fillStyle = color;
  ctx.lineWidth = 2;
  if (layer.shape === "polygon" && points.length > 1) {
    ctx.beginPath();
    points.forEach((p, i) => {
      const [sx, sy] = view.toScreen(p.x, p.y);
      if (i === 0) ctx.moveTo(sx, sy);
      else ctx.lineTo(sx, sy);
    });
    ctx.closePath();
    ctx.stroke();
  }
  for (const p of points) {
    const [sx, sy] = view.toScreen(p.x, p.y);
    ctx.beginPath();
    ctx.arc(sx, sy, 4.5, 0, 2 * Math.PI);
    ctx.fill();
    if (typeof p.yaw === "number") {
      line(ctx, sx, sy, sx + Math.cos(p.yaw) * 18, sy - Math.sin(p.yaw) * 18);
    }
  }
}

export function drawScaleBar(ctx, view) {
  const metres = [1, 2, 5, 10, 20].find((m) => m * view.scale >= 60) || 50;
  const px = metres * view.scale;
  const x = view.width - px - 14;
  const y = view.height - 22;
  ctx.strokeStyle = COLORS.text;
  ctx.lineWidth = 2;
  line(ctx, x, y, x + px, y);
  line(ctx, x, y - 4, x, y + 4);
  line(ctx, x + px, y - 4, x + px, y + 4);
  ctx.fillStyle = COLORS.text;
  ctx.font = "11px system-ui, sans-serif";
  ctx.textAlign = "center";
  ctx.textBaseline = "bottom";
  ctx.fillText(`${metres} m`, x + px / 2, y - 4);
}

function line(ctx, x0, y0, x1, y1) {
  ctx.beginPath();
  ctx.moveTo(x0, y0);
  ctx.lineTo(x1, y1);
  ctx.stroke();
}

// -- the robot world ---------------------------------------------------------------------------

/** The room's four walls, their inner faces at ±half metres, `thickness` thick. */
export function drawRoom(ctx, view, half, thickness) {
  const [x0, y0] = view.toScreen(-half - thickness, half + thickness);
  const [x1, y1] = view.toScreen(half + thickness, -half - thickness);
  const t = thickness * view.scale;
  ctx.fillStyle = COLORS.wall;
  ctx.fillRect(x0, y0, x1 - x0, t);
  ctx.fillRect(x0, y1 - t, x1 - x0, t);
  ctx.fillRect(x0, y0, t, y1 - y0);
  ctx.fillRect(x1 - t, y0, t, y1 - y0);
}

/** Box obstacles: {x, y, yaw, sx, sy} in metres. */
export function drawObstacles(ctx, view, obstacles) {
  for (const box of obstacles) {
    const [sx, sy] = view.toScreen(box.x, box.y);
    const w = box.sx * view.scale;
    const h = box.sy * view.scale;
    ctx.save();
    ctx.translate(sx, sy);
    ctx.rotate(-box.yaw);
    ctx.fillStyle = `${COLORS.obstacle}88`;
    ctx.strokeStyle = COLORS.obstacle;
    ctx.lineWidth = 1.5;
    ctx.fillRect(-w / 2, -h / 2, w, h);
    ctx.strokeRect(-w / 2, -h / 2, w, h);
    ctx.restore();
  }
}

/** People: two legs side by side across the way each faces. */
export function drawPeople(ctx, view, people, legRadius, legSpacing) {
  ctx.fillStyle = `${COLORS.person}aa`;
  ctx.strokeStyle = COLORS.person;
  ctx.lineWidth = 1.5;
  for (const person of people) {
    for (const side of [1, -1]) {
      const x = person.x - side * (legSpacing / 2) * Math.sin(person.yaw);
      const y = person.y + side * (legSpacing / 2) * Math.cos(person.yaw);
      const [sx, sy] = view.toScreen(x, y);
      ctx.beginPath();
      ctx.arc(sx, sy, Math.max(3, legRadius * view.scale), 0, 2 * Math.PI);
      ctx.fill();
      ctx.stroke();
    }
  }
}

/** A scan's points (in the laser frame) placed at the robot's pose. */
export function drawScan(ctx, view, pose, points) {
  const c = Math.cos(pose.yaw);
  const s = Math.sin(pose.yaw);
  ctx.fillStyle = COLORS.scan;
  for (const p of points) {
    const [sx, sy] = view.toScreen(pose.x + c * p.x - s * p.y, pose.y + s * p.x + c * p.y);
    ctx.fillRect(sx - 1.5, sy - 1.5, 3, 3);
  }
}

/** A robot at its size: a disc, its heading, a label; red where the bumper is pressed. */
export function drawRobot(ctx, view, pose, radius, label, bump, stale) {
  const [sx, sy] = view.toScreen(pose.x, pose.y);
  const r = Math.max(6, radius * view.scale);
  const color = stale ? "#7d8895" : COLORS.robot;
  const pressed = bump && (bump.left_front || bump.right_front || bump.left_side || bump.right_side);
  ctx.fillStyle = `${color}40`;
  ctx.strokeStyle = pressed ? COLORS.bump : color;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.arc(sx, sy, r, 0, 2 * Math.PI);
  ctx.fill();
  ctx.stroke();
  ctx.strokeStyle = color;
  line(ctx, sx, sy, sx + Math.cos(pose.yaw) * r, sy - Math.sin(pose.yaw) * r);
  ctx.font = "bold 11px system-ui, sans-serif";
  ctx.fillStyle = COLORS.text;
  ctx.textAlign = "left";
  ctx.textBaseline = "top";
  ctx.fillText(label, sx + r + 3, sy + 3);
}
