// Wires the dashboard together and exposes a read-only debug hook on `window.skydeck`.

import { Access } from "./access.js";
import { ActionsPanel } from "./actions.js";
import { setReadable, socketStates, updatePublished } from "./api.js";
import { initTokenButton } from "./auth.js";
import { CameraView } from "./camera.js";
import { ClassPage } from "./class_page.js";
import { Commands } from "./commands.js";
import { LogConsole } from "./console.js";
import { GraphPoller, GraphTables } from "./graph.js";
import { GraphDiagram } from "./graph_diagram.js";
import { Inspector } from "./inspector.js";
import { Layers } from "./layers.js";
import { LayersPanel } from "./layers_panel.js";
import { MapView } from "./map.js";
import { ParametersPanel } from "./parameters.js";
import { Plots } from "./plots.js";
import { ROBOT_TOPICS, Room, topicIn } from "./room.js";
import { RecorderPanel } from "./recorder.js";
import { StatusBanner } from "./status.js";
import { Tabs } from "./tabs.js";
import { Teleop } from "./teleop.js";
import { View3DLoader } from "./view3d/loader.js";
import { WindowsView } from "./windows.js";
import { DRONE_TOPICS, World } from "./world.js";

const $ = (id) => document.getElementById(id);

// What the page's token may do: in a class, a student's page reads and lists only what their
// token may read (access.js); the instructor's has the Class tab.
const access = new Access();
setReadable((topic) => access.mayRead(topic));

const world = new World();
const room = new Room(); // the robot world's state, started when /simulator/world says so
const graph = new GraphPoller();
const layers = new Layers();
const tabs = new Tabs(document.querySelector(".tabs"));
// The main view: the 2D map or the 3D view (remembered across reloads).
const viewTabs = new Tabs($("map-panel"));
const view3d = new View3DLoader($("view3d"));
const windows = new WindowsView({ tab: $("windows-tab"), list: $("windows-list"), empty: $("windows-empty") });
viewTabs.addEventListener("change", () => {
  view3d.setShown(viewTabs.current === "view3d");
  windows.setShown(viewTabs.current === "windows");
  classPage.setShown(viewTabs.current === "class");
  if (viewTabs.current !== "class") localStorage.setItem("skydeck.view", viewTabs.current);
});

const commands = new Commands({
  buttons: [...document.querySelectorAll("#commands-panel [data-service]")],
  result: $("command-result"),
});
commands.addEventListener("answer", (event) => {
  if (event.detail.service === "/simulator/reset" && event.detail.kind === "success") {
    world.clearTrack();
    room.clearTrails();
  }
});

const map = new MapView($("map"), {
  world,
  room,
  layers,
  follow: $("map-follow"),
  cursorLabel: $("map-cursor"),
  onClick: (x, y) => {
    if (world.kind === "robot" || !$("click-to-fly").checked) return;
    world.flyTarget = { x, y };
    commands.fly(x, y);
  },
});
$("map-fit").addEventListener("click", () => {
  $("map-follow").checked = false;
  map.fit();
});

const inspector = new Inspector(
  {
    form: $("inspect-form"),
    name: $("inspect-name"),
    names: $("inspect-names"),
    info: $("inspect-info"),
    typeText: $("inspect-type-text"),
    echoBox: $("inspect-echo-box"),
    echo: $("inspect-echo"),
    pause: $("inspect-pause"),
    stats: $("inspect-stats"),
    sendBox: $("inspect-send-box"),
    sendTitle: $("inspect-send-title"),
    typeRow: $("inspect-type-row"),
    type: $("inspect-type"),
    fields: $("inspect-fields"),
    json: $("inspect-json"),
    send: $("inspect-send"),
    repeat: $("inspect-repeat"),
    repeatRow: $("inspect-repeat-row"),
    result: $("inspect-result"),
  },
  graph,
);
const pick = (name) => {
  tabs.show("inspector");
  inspector.inspect(name);
};
const classPage = new ClassPage({
  tab: $("class-tab"),
  table: $("class-table"),
  detail: $("class-detail"),
  assignment: $("class-assignment"),
  note: $("class-note"),
  canvas: $("class-canvas"),
  graph,
  onPick: pick,
});
const tables = new GraphTables({ topics: $("topic-list"), services: $("service-list"), nodes: $("node-list"), onPick: pick });
const diagram = new GraphDiagram({ container: $("graph-diagram"), showDebug: $("graph-show-debug"), onPick: pick });
const layersPanel = new LayersPanel({
  layers,
  select: $("add-topic-select"),
  color: $("add-topic-color"),
  form: $("add-topic-form"),
  list: $("layer-list"),
});
const parameters = new ParametersPanel({ node: $("param-node"), table: $("param-list"), result: $("param-result"), refresh: $("param-refresh") });
const actions = new ActionsPanel({ table: $("action-list"), empty: $("action-empty") });

graph.addEventListener("update", () => {
  commands.updateGraph(graph.graph);
  if (!graph.graph) return;
  updatePublished(graph.graph); // first: the sockets waiting for a publisher open

  tables.render(graph.graph);
  if (tabs.current === "graph") diagram.render(graph.graph);
  inspector.updateGraph(graph.graph);
  layersPanel.updateGraph(graph.graph);
  parameters.updateGraph(graph.graph);
  actions.updateGraph(graph.graph);
  view3d.updateGraph(graph.graph);
  windows.updateGraph(graph.graph);
});
function expandGraph(expanded) {
  const button = $("graph-expand");
  button.closest(".tab").classList.toggle("expanded", expanded);
  button.textContent = expanded ? "Close" : "Expand";
  button.setAttribute("aria-pressed", String(expanded));
}
$("graph-expand").addEventListener("click", (event) => expandGraph(event.target.getAttribute("aria-pressed") !== "true"));
window.addEventListener("keydown", (event) => {
  if (event.key === "Escape") expandGraph(false);
});
tabs.addEventListener("change", () => {
  if (tabs.current === "graph" && graph.graph) diagram.render(graph.graph);
  parameters.setVisible(tabs.current === "parameters");
  actions.setVisible(tabs.current === "actions");
});

const teleop = new Teleop({
  toggle: $("teleop-toggle"),
  speed: $("teleop-speed"),
  speedLabel: $("teleop-speed-value"),
  keysView: $("teleop-keys"),
  note: $("teleop-note"),
  topicLabel: $("teleop-topic"),
});
const camera = new CameraView({
  toggle: $("camera-toggle"),
  kind: $("camera-kind"),
  figure: $("camera-view"),
  image: $("camera-image"),
  canvas: $("camera-canvas"),
  caption: $("camera-caption"),
});
const log = new LogConsole({
  container: $("log"),
  level: $("log-level"),
  node: $("log-node"),
  filter: $("log-filter"),
  clear: $("log-clear"),
  count: $("log-count"),
});
const status = new StatusBanner({ banner: $("status-banner"), pill: $("core-status"), summary: $("drone-summary"), graph, world, room });

function renderMission() {
  const s = world.aiStatus;
  if (!s) return;
  const visited = (s.visited || []).length;
  const total = visited + (s.remaining ?? 0);
  const target = s.target >= 0 ? `, heading to box ${s.target}` : "";
  const length = typeof s.tour_length === "number" ? `, tour ${s.tour_length.toFixed(1)} m` : "";
  $("mission-status").textContent = `mission: ${s.state} · ${visited}/${total} boxes visited${target}${length}${s.message ? ` · ${s.message}` : ""}`;
  $("mission-status").dataset.state = s.state;
}
world.addEventListener("ai-status", renderMission);

initTokenButton($("token-button"));
graph.filter = (g) => access.filterGraph(g);
access.addEventListener("change", () => {
  setReadable((topic) => access.mayRead(topic));
  graph.refilter();
  classPage.setAvailable(access.isInstructor);
  if (access.isInstructor && location.hash === "#class") viewTabs.show("class");
  if (world.kind) applyWorld(); // a student's robots only
});
window.addEventListener("skydeck-token", () => access.refresh());
access.refresh();
tabs.show("topics");
viewTabs.show(["view3d", "windows"].includes(localStorage.getItem("skydeck.view")) ? localStorage.getItem("skydeck.view") : "map");
world.start();
graph.start();
layers.restore();
log.start();
map.start();
const plots = new Plots({ world, altitude: $("plot-altitude"), speed: $("plot-speed") });
plots.start();

// The world the simulator runs decides what the map, plots, teleop and commands show.
function applyWorld() {
  const kind = world.kind || "drone";
  for (const element of document.querySelectorAll("[data-world]")) element.hidden = element.dataset.world !== kind;
  const robots = $("teleop-robot");
  if (kind === "robot") {
    // In a class, a student's robot only: the one whose odometry their token may read.
    const namespaces = world.namespaces.filter((ns) => access.mayRead(topicIn(ns, ROBOT_TOPICS.odom)));
    room.start(namespaces);
    plots.use(room, "robot");
    robots.replaceChildren(...namespaces.map((ns) => new Option(ns === "/" ? "robot" : ns.slice(1), ns)));
    robots.hidden = namespaces.length < 2;
    teleop.setTarget("robot", topicIn(namespaces[0] || "/", ROBOT_TOPICS.cmd_vel));
  } else {
    room.stop();
    plots.use(world, "drone");
    robots.hidden = true;
    teleop.setTarget("drone", DRONE_TOPICS.cmd_vel);
  }
  map.fit();
}
world.addEventListener("world", applyWorld);
$("teleop-robot").addEventListener("change", (event) => teleop.setTarget("robot", topicIn(event.target.value, ROBOT_TOPICS.cmd_vel)));
status.start();
const recorder = new RecorderPanel({ toggle: $("record-toggle"), status: $("record-status"), list: $("recording-list") });
recorder.start();

const copy = (value) => (value == null ? null : structuredClone(value));

// Read-only view of the dashboard's state for tests and curious users (open the console).
window.skydeck = Object.freeze({
  get pose() {
    return copy(world.pose);
  },
  /** Which world the simulator runs: {kind: "drone" | "robot" | null, namespaces}. */
  get world() {
    return { kind: world.kind, namespaces: [...world.namespaces] };
  },
  /** The robot world: per robot its true pose, odometry, trail and scan sizes, bumper; the room. */
  get room() {
    return {
      robots: room.robots.map((r) => ({
        namespace: r.namespace,
        pose: copy(r.pose),
        odom: copy(r.odom),
        trail: r.trail.length,
        scanPoints: r.scan ? r.scan.points.length : 0,
        bump: copy(r.bump),
      })),
      obstacles: copy(room.obstacles),
      people: copy(room.people),
    };
  },
  get track() {
    return copy(world.track);
  },
  get boxes() {
    return { simulator: copy(world.simBoxes), perception: copy(world.perceptionBoxes) };
  },
  get aiStatus() {
    return copy(world.aiStatus);
  },
  get controlState() {
    return copy(world.controlState);
  },
  get graph() {
    return copy(graph.graph);
  },
  get coreReachable() {
    return graph.graph !== null && graph.error === null;
  },
  get lastCommand() {
    return copy(commands.last);
  },
  get teleop() {
    return { enabled: teleop.enabled, held: [...teleop.held], sent: teleop.sent, twist: teleop.twist(), topic: teleop.topic };
  },
  get camera() {
    return { shown: !camera.figure.hidden, topic: camera.topic, frames: camera.frames, error: camera.error };
  },
  get log() {
    return log.entries.map((e) => ({ ...e }));
  },
  get mapFrames() {
    return map.frames;
  },
  get banner() {
    return { state: $("status-banner").dataset.state, text: status.message };
  },
  get parameters() {
    return { node: parameters.node, rows: copy(parameters.rows), last: copy(parameters.last) };
  },
  /** The Actions tab's rows (while it is shown): [{action, type, goal, status, feedback}]. */
  get actions() {
    return actions.snapshot();
  },
  get recorder() {
    return { recording: recorder.recording, current: copy(recorder.current), files: copy(recorder.files), error: recorder.error };
  },
  layers: () => layers.snapshot(),
  sockets: () => socketStates(),
  /** Client (page) coordinates of map point (x, y): where to click to fly there. */
  worldToClient: (x, y) => map.worldToClient(x, y),
  clientToWorld: (x, y) => map.clientToWorld(x, y),
  /** The OpenCV windows of programs (the Windows tab): per window its description, frames shown, sliders, input sent. */
  get windows() {
    return windows.snapshot();
  },
  /** Client (page) coordinates of pixel (x, y) of the window whose image topic is `topic` (null if none). */
  windowPoint: (topic, x, y) => windows.panel(topic)?.clientPoint(x, y) ?? null,
  /** The 3D view: fixed frame, frames, camera, world, displays (what each draws, in the fixed frame), frame times. */
  view3d: (options) => view3d.snapshot(options),
  /** The page's token as the core described it (GET /api/access), and the class page's state. */
  get access() {
    return copy(access.described);
  },
  get classPage() {
    return classPage.snapshot();
  },
});

function renderLegendLayers() {
  const box = $("legend-layers");
  box.replaceChildren();
  for (const layer of layers.list()) {
    const item = document.createElement("span");
    const swatch = document.createElement("i");
    swatch.style.background = layer.color;
    item.append(swatch, document.createTextNode(layer.topic));
    box.append(item);
  }
}
layers.addEventListener("change", renderLegendLayers);
renderLegendLayers();
