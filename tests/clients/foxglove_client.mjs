// @foxglove/ws-protocol's FoxgloveClient (from npm) driving Skydeck's Foxglove endpoint.
//
//     node foxglove_client.mjs URL SCENARIO [SUBPROTOCOL]
//
// Prints one JSON object per line for the test to check; exits 0 when the scenario ran.
import foxglove from "@foxglove/ws-protocol";
import WebSocket from "ws";

const { FoxgloveClient } = foxglove; // a CommonJS package

const [url, scenario, subprotocol = FoxgloveClient.SUPPORTED_SUBPROTOCOL] = process.argv.slice(2);
const emit = (values) => console.log(JSON.stringify(values, (_, v) => (typeof v === "bigint" ? Number(v) : v)));
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
const encoder = new TextEncoder();
const decoder = new TextDecoder();
const text = (view) => decoder.decode(new Uint8Array(view.buffer, view.byteOffset, view.byteLength));

// Every event the client raises, kept so a scenario can wait for the one it needs.
const events = [];
const waiting = [];
function record(name, value) {
  events.push({ name, value });
  for (const waiter of [...waiting]) {
    if (waiter.name === name && waiter.test(value)) {
      waiting.splice(waiting.indexOf(waiter), 1);
      waiter.resolve(value);
    }
  }
}
function next(name, test = () => true, ms = 10000) {
  const seen = events.find((event) => event.name === name && test(event.value));
  if (seen) {
    events.splice(events.indexOf(seen), 1);
    return Promise.resolve(seen.value);
  }
  return new Promise((resolve, reject) => {
    const waiter = { name, test, resolve };
    waiting.push(waiter);
    setTimeout(() => reject(new Error(`no ${name} event within ${ms} ms`)), ms);
  });
}

const client = new FoxgloveClient({ ws: new WebSocket(url, [subprotocol]) });
const channels = new Map();
const services = new Map();
for (const name of ["serverInfo", "status", "message", "time", "parameterValues", "serviceCallResponse",
  "serviceCallFailure", "connectionGraphUpdate", "unadvertise", "close", "error"]) {
  client.on(name, (value) => record(name, value));
}
client.on("advertise", (added) => {
  for (const channel of added) channels.set(channel.topic, channel);
  record("advertise", added);
});
client.on("advertiseServices", (added) => {
  for (const service of added) services.set(service.name, service);
  record("advertiseServices", added);
});

async function channel(topic) {
  if (!channels.has(topic)) await next("advertise", (added) => added.some((c) => c.topic === topic));
  return channels.get(topic);
}

async function service(name) {
  if (!services.has(name)) await next("advertiseServices", (added) => added.some((s) => s.name === name));
  return services.get(name);
}

let callIds = 0;
async function callService(name, request) {
  const { id } = await service(name);
  const callId = ++callIds;
  const payload = encoder.encode(JSON.stringify(request));
  client.sendServiceCallRequest({ serviceId: id, callId, encoding: "json", data: new DataView(payload.buffer) });
  const answer = await Promise.race([
    next("serviceCallResponse", (r) => r.callId === callId).then((r) => ({ response: JSON.parse(text(r.data)), encoding: r.encoding })),
    next("serviceCallFailure", (f) => f.callId === callId).then((f) => ({ failure: f.message })),
  ]);
  return answer;
}

async function tour() {
  emit({ serverInfo: await next("serverInfo") });
  const pose = await channel("/drone/pose");
  emit({ channel: pose, topics: [...channels.keys()] });
  const takeOff = await service("/control/take_off");
  emit({ service: takeOff });
  const subscription = client.subscribe(pose.id);
  const message = await next("message", (m) => m.subscriptionId === subscription);
  emit({ message: JSON.parse(text(message.data)), timestamp: message.timestamp, subscription });
  const time = await next("time");
  emit({ time: time.timestamp });
  client.unsubscribe(subscription);
  const name = await channel("/drone/name");
  const latchedSub = client.subscribe(name.id);
  const latched = await next("message", (m) => m.subscriptionId === latchedSub);
  emit({ latched: JSON.parse(text(latched.data)) });
  // Teleop, as Foxglove's panel does it: advertise with the ROS 1 style name, then publish.
  const cmdVel = client.advertise({ topic: "/drone/cmd_vel", encoding: "json", schemaName: "geometry_msgs/Twist" });
  await sleep(1000);
  for (const x of [3.0, 3.5]) {
    client.sendMessage(cmdVel, encoder.encode(JSON.stringify({ linear: { x, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } })));
  }
  emit({ published: 2 });
  emit({ take_off: await callService("/control/take_off", {}) });
  emit({ bad_call: await callService("/control/take_off", { nonsense: 1 }) });
  client.subscribeConnectionGraph();
  emit({ graph: await next("connectionGraphUpdate") });
  client.unadvertise(cmdVel);
}

async function parameters() {
  await next("serverInfo");
  const [name, value] = process.argv.slice(5);
  client.getParameters([], "all");
  emit({ all: (await next("parameterValues", (p) => p.id === "all")).parameters });
  client.subscribeParameterUpdates([name]);
  await sleep(1000); // the core links to the nodes' /parameter_events in a moment
  client.setParameters([{ name, value: JSON.parse(value) }], "set");
  emit({ set: (await next("parameterValues", (p) => p.id === "set")).parameters });
  emit({ update: (await next("parameterValues", (p) => p.id === undefined)).parameters });
  emit({ statuses: events.filter((e) => e.name === "status").map((e) => e.value) });
}

// A request's answer, or the status it got: the server answers ops in order, so a barrier
// (getParameters with an id of its own) after the request says "no status came for it".
let barriers = 0;
async function statusOrNothing(text) {
  const id = `barrier-${++barriers}`;
  client.getParameters(["/none.none"], id);
  await next("parameterValues", (p) => p.id === id);
  const status = events.find((e) => e.name === "status" && e.value.message.includes(text));
  return status ? status.value.message : null;
}

async function callIfShown(name, request) {
  if (!services.has(name)) return { hidden: true };
  return callService(name, request);
}

// Each verb the fences guard, on the names of the namespace given, as the URL's token may do it.
async function fences() {
  const target = process.argv[5];
  await next("serverInfo");
  await next("advertise");
  await sleep(200); // the first advertiseServices follows the first advertise at once
  const scan = `/${target}/scan`;
  if (channels.has(scan)) {
    const sub = client.subscribe(channels.get(scan).id);
    const answer = await Promise.race([
      next("message", (m) => m.subscriptionId === sub).then((m) => ({ message: JSON.parse(text(m.data)) })),
      next("status", (s) => s.message.includes(scan)).then((s) => ({ status: s.message })),
    ]);
    emit({ verb: "read", ...answer });
  } else {
    emit({ verb: "read", hidden: true, shared: channels.has("/clock") });
  }
  const topic = `/${target}/cmd_vel`;
  const cmdVel = client.advertise({ topic, encoding: "json", schemaName: "geometry_msgs/msg/Twist" });
  const refused = await statusOrNothing(topic);
  if (!refused) {
    await sleep(1000); // subscribers link to the new publisher in a moment, as with ROS
    client.sendMessage(cmdVel, encoder.encode(JSON.stringify({ linear: { x: 0.75, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } })));
  }
  emit({ verb: "publish", status: refused });
  emit({ verb: "call", ...(await callIfShown(`/${target}/ping`, {})) });
  const gain = `/${target}/driver.gain`;
  client.setParameters([{ name: gain, value: 2.5 }], "gain");
  const set = await Promise.race([
    next("parameterValues", (p) => p.id === "gain").then((p) => ({ values: p.parameters })),
    next("status", (s) => s.message.includes(`/${target}/driver`)).then((s) => ({ status: s.message })),
  ]);
  emit({ verb: "set_parameter", ...set });
  emit({ verb: "kill_node", ...(await callIfShown("/skydeck_launch/kill_node", { node: `/${target}/driver` })) });
  emit({ verb: "reset_world", ...(await callIfShown("/simulator/reset", {})) });
  emit({ after: await statusOrNothing("nothing at all") }); // the connection carries on
}

try {
  await { tour, parameters, fences }[scenario]();
  client.close();
  process.exit(0);
} catch (error) {
  console.error(error.stack || String(error));
  console.error(JSON.stringify(events.map((e) => e.name)));
  process.exit(1);
}
