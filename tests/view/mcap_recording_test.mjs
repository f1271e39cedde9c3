// `edgevio run --mcap`: the recording read back by an independent reader,
// @mcap/core (the MCAP project's own TypeScript library, from npm). Every
// channel and schema is there; the per-frame channels hold one message per
// frames.csv row, the pictures' channel one per kept picture, the
// keyframes' one per keyframe, the paths' one per second of sensor time
// and one at the end, the last holding the whole path; times increase; the summary agrees; the
// messages are the JSON their schemas say. And writing it changes nothing
// in the run's trajectory.
// Usage: node mcap_recording_test.mjs EDGEVIO_EXE WORK_DIR
import { readFileSync, readdirSync, rmSync, mkdirSync } from 'node:fs';
import { check, edgevio, requirePackage } from './browser.mjs';

const { McapStreamReader, McapIndexedReader } = requirePackage('@mcap/core');
const [exe, work] = process.argv.slice(2);
rmSync(work, { recursive: true, force: true });
mkdirSync(work, { recursive: true });
edgevio(exe, ['simulate', '--scenario', 'figure8', '--duration', '3', '--seed', '5', '--out', `${work}/data`]);
edgevio(exe, ['run', `${work}/data`, '--out', `${work}/run`, '--mcap', `${work}/run.mcap`]);
edgevio(exe, ['run', `${work}/data`, '--out', `${work}/plain`]);

check(readFileSync(`${work}/run/trajectory.csv`, 'utf8') === readFileSync(`${work}/plain/trajectory.csv`, 'utf8'),
      'the trajectory is bit-identical with and without --mcap');

const lines = readFileSync(`${work}/run/frames.csv`, 'utf8').trim().split('\n');
const header = lines[0].split(',');
const rows = lines.slice(1).map(l => l.split(','));
const keyframes = rows.filter(r => r[header.indexOf('keyframe')] === '1').length;
const pictures = readdirSync(`${work}/run/alignment`).length;
// Paths: at the first frame, then at each frame a second or more after the
// last sent, and at the last frame (recording.h).
const times = rows.map(r => BigInt(r[header.indexOf('timestamp_ns')]));
let pathSends = 0, sent = -1n;
for (const t of times) if (sent < 0n || t - sent >= 1000000000n) { ++pathSends; sent = t; }
if (sent !== times[times.length - 1]) ++pathSends;

const bytes = readFileSync(`${work}/run.mcap`);
const reader = new McapStreamReader();
reader.append(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength));
const schemas = new Map(), channels = new Map(), messages = new Map();
let header0 = null, statistics = null;
for (let record; (record = reader.nextRecord());) {
  if (record.type === 'Header') header0 = record;
  if (record.type === 'Schema') schemas.set(record.id, record);
  if (record.type === 'Channel') channels.set(record.id, record);
  if (record.type === 'Statistics') statistics = record;
  if (record.type === 'Message') {
    if (!messages.has(record.channelId)) messages.set(record.channelId, []);
    messages.get(record.channelId).push(record);
  }
}
check(reader.done(), 'the stream reader reached a valid footer and closing magic');
check(header0 && header0.library === 'edgevio', 'the header names its writer');

const expected = {
  '/tf': ['foxglove.FrameTransforms', rows.length],
  '/pose': ['foxglove.PoseInFrame', rows.length],
  '/path/estimate': ['foxglove.PosesInFrame', pathSends],
  '/path/ground_truth': ['foxglove.PosesInFrame', pathSends],
  '/keyframes': ['foxglove.PosesInFrame', keyframes],
  '/alignment': ['foxglove.CompressedImage', pictures],
  '/frame': ['edgevio.FrameRecord', rows.length],
  '/events': ['foxglove.Log', null],
};
const byTopic = new Map([...channels.values()].map(c => [c.topic, c]));
for (const [topic, [schemaName, count]] of Object.entries(expected)) {
  const c = byTopic.get(topic);
  check(c && c.messageEncoding === 'json', `channel ${topic} is present, JSON-encoded`);
  const schema = schemas.get(c.schemaId);
  check(schema && schema.name === schemaName && schema.encoding === 'jsonschema', `${topic} has schema ${schemaName} (jsonschema)`);
  JSON.parse(new TextDecoder().decode(schema.data));
  const got = (messages.get(c.id) || []);
  if (count !== null) check(got.length === count, `${topic}: ${got.length} messages, expected ${count}`);
  let increasing = true;
  for (let i = 1; i < got.length; ++i) increasing &&= got[i].logTime > got[i - 1].logTime || (topic === '/events' && got[i].logTime === got[i - 1].logTime);
  check(increasing, `${topic}: timestamps increase`);
  for (const m of got) JSON.parse(new TextDecoder().decode(m.data));
}
check(channels.size === Object.keys(expected).length, `no other channel (${channels.size})`);

// The per-frame messages are the frames, in order, at the frames' times.
const frameMessages = messages.get(byTopic.get('/frame').id);
const t = header.indexOf('timestamp_ns');
check(frameMessages.every((m, i) => m.logTime === BigInt(rows[i][t])), '/frame messages carry the frames\' timestamps');
const first = JSON.parse(new TextDecoder().decode(frameMessages[0].data));
check(Object.keys(first).length === header.length && String(first.timestamp_ns) === rows[0][t],
      '/frame messages have one field per frames.csv column');
const image = JSON.parse(new TextDecoder().decode(messages.get(byTopic.get('/alignment').id)[0].data));
const jpeg = Buffer.from(image.data, 'base64');
check(image.format === 'jpeg' && jpeg[0] === 0xff && jpeg[1] === 0xd8, 'the alignment pictures are base64 JPEG');
const paths = messages.get(byTopic.get('/path/estimate').id);
const lastPath = JSON.parse(new TextDecoder().decode(paths[paths.length - 1].data));
check(paths[paths.length - 1].logTime === times[times.length - 1] && lastPath.poses.length === rows.length,
      `the last path, at the last frame, holds every frame's pose (${lastPath.poses.length})`);
const tf = JSON.parse(new TextDecoder().decode(messages.get(byTopic.get('/tf').id)[0].data));
check(tf.transforms.map(x => `${x.parent_frame_id}>${x.child_frame_id}`).join(' ') === 'world>body body>cam0 body>cam1',
      '/tf holds world → body → cam0, cam1');

// The summary section, as the indexed reader (what Foxglove uses) sees it.
const indexed = await McapIndexedReader.Initialize({
  readable: { size: async () => BigInt(bytes.length), read: async (o, n) => new Uint8Array(bytes.buffer, bytes.byteOffset + Number(o), Number(n)) },
});
const total = [...messages.values()].reduce((n, m) => n + m.length, 0);
check(indexed.statistics && indexed.statistics.messageCount === BigInt(total), `the summary's statistics count ${total} messages`);
check(indexed.channelsById.size === channels.size && indexed.schemasById.size === schemas.size, 'the summary lists every channel and schema');
check(statistics && statistics.channelMessageCounts.get(byTopic.get('/frame').id) === BigInt(rows.length),
      'the statistics count the messages of each channel');
