// Wires the dashboard together and exposes a read-only debug hook on `window.skydeck`.

import { socketStates } from "./api.js";
import { initTokenButton } from "./auth.js";
import { CameraView } from "./camera.js";
import { Commands } from "./commands.js";
import { LogConsole } from "./console.js";
import { GraphPoller, GraphTables } from "./graph.js";
import { GraphDiagram } from "./graph_diagram.js";
import { Inspector } from "./inspector.js";
import { Layers } from "./layers.js";
import { LayersPanel } from "./layers_panel.js";
import { MapView } from "./map.js";
import { Plots } from "./plots.js";
import { RecorderPanel } from "./recorder.js";
import { StatusBanner } from "./status.js";
import { Tabs } from "./tabs.js";
import { Teleop } from "./teleop.js";
import { World } from "./world.js";

const $ = (id) => document.getElementById(id);

const world = new World();
const graph = new GraphPoller();
const layers = new Layers();
const tabs = new Tabs(document.querySelector(".tabs"));

const commands = new Commands({
  buttons: [...document.querySelectorAll("#commands-panel [data-service]")],
  result: $("command-result"),
});
commands.addEventListener("answer", (event) => {
  if (event.detail.service === "/simulator/reset" && event.detail.kind === "success") world.clearTrack();
});

const map = new MapView($("map"), {
  world,
  layers,
  follow: $("map-follow"),
  cursorLabel: $("map-cursor"),
  onClick: (x, y) => {
    if (!$("click-to-fly").checked) return;
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
const tables = new GraphTables({ topics: $("topic-list"), services: $("service-list"), nodes: $("node-list"), onPick: pick });
const diagram = new GraphDiagram({ container: $("graph-diagram"), showDebug: $("graph-show-debug"), onPick: pick });
const layersPanel = new LayersPanel({
  layers,
  select: $("add-topic-select"),
  color: $("add-topic-color"),
  form: $("add-topic-form"),
  list: $("layer-list"),
});

graph.addEventListener("update", () => {
  commands.updateGraph(graph.graph);
  if (!graph.graph) return;
  tables.render(graph.graph);
  if (tabs.current === "graph") diagram.render(graph.graph);
  inspector.updateGraph(graph.graph);
  layersPanel.updateGraph(graph.graph);
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
});

const teleop = new Teleop({
  toggle: $("teleop-toggle"),
  speed: $("teleop-speed"),
  speedLabel: $("teleop-speed-value"),
  keysView: $("teleop-keys"),
  note: $("teleop-note"),
});
const camera = new CameraView({ toggle: $("camera-toggle"), figure: $("camera-view"), image: $("camera-image"), caption: $("camera-caption") });
const log = new LogConsole({
  container: $("log"),
  level: $("log-level"),
  node: $("log-node"),
  filter: $("log-filter"),
  clear: $("log-clear"),
  count: $("log-count"),
});
const status = new StatusBanner({ banner: $("status-banner"), pill: $("core-status"), summary: $("drone-summary"), graph, world });

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
tabs.show("topics");
world.start();
graph.start();
layers.restore();
log.start();
map.start();
new Plots({ world, altitude: $("plot-altitude"), speed: $("plot-speed") }).start();
status.start();
const recorder = new RecorderPanel({ toggle: $("record-toggle"), status: $("record-status"), list: $("recording-list") });
recorder.start();

const copy = (value) => (value == null ? null : structuredClone(value));

// Read-only view of the dashboard's state for tests and curious users (open the console).
window.skydeck = Object.freeze({
  get pose() {
    return copy(world.pose);
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
    return { enabled: teleop.enabled, held: [...teleop.held], sent: teleop.sent, twist: teleop.twist() };
  },
  get camera() {
    return { shown: !camera.figure.hidden, frames: camera.frames };
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
  get recorder() {
    return { recording: recorder.recording, current: copy(recorder.current), files: copy(recorder.files), error: recorder.error };
  },
  layers: () => layers.snapshot(),
  sockets: () => socketStates(),
  /** Client (page) coordinates of map point (x, y): where to click to fly there. */
  worldToClient: (x, y) => map.worldToClient(x, y),
  clientToWorld: (x, y) => map.clientToWorld(x, y),
});

function renderLegendLayers() {
  const box = $("legend-layers");
  box.replaceChildren();
  for (const layer of layers.list()) {
    const swatch = document.createElement("i");
    swatch.style.background = layer.color;
    box.append(swatch, document.createTextNode(layer.topic));
  }
}
layers.addEventListener("change", renderLegendLayers);
renderLegendLayers();
