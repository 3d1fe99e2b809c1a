// roslib (roslibjs, from npm) driving Skydeck's rosbridge endpoint: one scenario per run.
//
//     node roslibjs_client.mjs URL SCENARIO
//
// Prints one JSON object per line for the test to check; exits 0 when the scenario ran.
// TF: tf_ros1 (ROSLIB.TFClient: ROS 1's actionlib action /tf2_web_republisher over rosbridge
// topics) and tf_ros2 (ROSLIB.ROS2TFClient: ROS 2's action, send_action_goal) follow the carrot
// and the post in the world frame until the carrot has moved five times.
import { ROS2TFClient, Ros, Service, TFClient, Topic } from "roslib";

const [url, scenario] = process.argv.slice(2);
const emit = (values) => console.log(JSON.stringify(values));
const fail = (why) => {
  console.error(why);
  process.exit(1);
};
const within = (ms, what, promise) =>
  Promise.race([promise, new Promise((_, reject) => setTimeout(() => reject(new Error(`${what}: no answer in ${ms} ms`)), ms))]);
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

function firstMessage(ros, name, messageType) {
  return within(10000, name, new Promise((resolve) => {
    const topic = new Topic({ ros, name, messageType });
    topic.subscribe((message) => {
      topic.unsubscribe();
      resolve(message);
    });
  }));
}

function call(ros, name, serviceType, request) {
  return within(10000, name, new Promise((resolve) => {
    new Service({ ros, name, serviceType }).callService(
      request,
      (response) => resolve({ response }),
      (error) => resolve({ error }),
    );
  }));
}

async function tour(ros) {
  emit({ pose: await firstMessage(ros, "/drone/pose", "geometry_msgs/msg/PoseStamped") });
  emit({ latched: await firstMessage(ros, "/drone/name", "std_msgs/msg/String") });
  const cmdVel = new Topic({ ros, name: "/drone/cmd_vel", messageType: "geometry_msgs/msg/Twist" });
  cmdVel.advertise();
  await sleep(1000); // subscribers link to a new publisher in a moment, as in ROS
  for (const x of [2.0, 2.5]) cmdVel.publish({ linear: { x, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } });
  emit({ published: 2 });
  emit({ take_off: await call(ros, "/control/take_off", "std_srvs/srv/Trigger", {}) });
  emit({ topics: await within(10000, "getTopics", new Promise((resolve, reject) => ros.getTopics(resolve, reject))) });
  emit({ typedefs: await within(10000, "getMessageDetails",
    new Promise((resolve, reject) => ros.getMessageDetails("geometry_msgs/msg/PoseStamped", resolve, reject))) });
  emit({ missing: await call(ros, "/no/such/service", "std_srvs/srv/Trigger", {}) });
  cmdVel.unadvertise();
}

async function host(ros) {
  const service = new Service({ ros, name: "/demo/echo_js", serviceType: "std_srvs/srv/SetBool" });
  await service.advertise((request, response) => {
    response.success = request.data;
    response.message = "from roslibjs";
    return true;
  });
  await sleep(500);
  emit({ advertised: "/demo/echo_js" });
  // Another rosbridge client (this one, on a second connection) calls it through the core.
  const other = await connect(url);
  emit({ called: await call(other, "/demo/echo_js", "std_srvs/srv/SetBool", { data: true }) });
  other.close();
}

async function follow(ros, Client) {
  const client = new Client({ ros, fixedFrame: "world", angularThres: 0.01, transThres: 0.01, rate: 20.0 });
  const carrots = [];
  const posts = [];
  client.subscribe("post", (transform) => posts.push(transform));
  await within(20000, "five carrot transforms", new Promise((resolve) => {
    client.subscribe("/carrot", (transform) => {
      carrots.push({ translation: { ...transform.translation }, rotation: { ...transform.rotation } });
      if (carrots.length === 5) resolve();
    });
  }));
  emit({ carrots, posts: posts.map((transform) => ({ translation: { ...transform.translation } })) });
  client.dispose();
  await sleep(300); // the cancel goes out before the connection closes
}

function connect(address) {
  return within(10000, "connection", new Promise((resolve, reject) => {
    const ros = new Ros({ url: address });
    ros.on("connection", () => resolve(ros));
    ros.on("error", (error) => reject(new Error(`connection error: ${error}`)));
  }));
}

try {
  const ros = await connect(url);
  emit({ connected: true });
  const scenarios = { tour, host, tf_ros1: () => follow(ros, TFClient), tf_ros2: () => follow(ros, ROS2TFClient) };
  await scenarios[scenario](ros);
  ros.close();
  process.exit(0);
} catch (error) {
  fail(error.stack || String(error));
}
