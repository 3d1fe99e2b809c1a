// roslib's (roslibjs, from npm) TF clients against Skydeck's tf2_web_republisher: one scenario per run.
//
//     node roslibjs_tf.mjs URL SCENARIO
//
//     ros1   ROSLIB.TFClient: ROS 1's actionlib action /tf2_web_republisher over rosbridge topics
//     ros2   ROSLIB.ROS2TFClient: ROS 2's action /tf2_web_republisher over send_action_goal
//
// Follows the carrot and the post in the world frame until the carrot has moved five times, then
// prints one JSON object and disposes of the client; exits 0 when the scenario ran.
import { ROS2TFClient, Ros, TFClient } from "roslib";

const [url, scenario] = process.argv.slice(2);
const emit = (values) => console.log(JSON.stringify(values));
const fail = (why) => {
  console.error(why);
  process.exit(1);
};
const within = (ms, what, promise) =>
  Promise.race([promise, new Promise((_, reject) => setTimeout(() => reject(new Error(`${what}: no answer in ms ${ms}`)), ms))]);
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

function connect(address) {
  return within(10000, "connection", new Promise((resolve, reject) => {
    const ros = new Ros({ url: address });
    ros.on("connection", () => resolve(ros));
    ros.on("error", (error) => reject(new Error(`connection error: ${error}`)));
  }));
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

try {
  const ros = await connect(url);
  emit({ connected: true });
  await follow(ros, { ros1: TFClient, ros2: ROS2TFClient }[scenario]);
  ros.close();
  process.exit(0);
} catch (error) {
  fail(error.stack || String(error));
}
