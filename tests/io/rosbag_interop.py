#!/usr/bin/python3
"""ROS 1 bags written and read by ROS's own Python library (Debian's
python3-rosbag), to check edgevio's reader and writer against an
independent implementation. Images are 8-bit grey PNGs, decoded here with
zlib alone (no numpy or OpenCV in Debian's python3-rosbag world).

  rosbag_interop.py write ASL_FOLDER OUT.bag COMPRESSION IMAGES GROUNDTRUTH
      COMPRESSION none | bz2 | lz4; IMAGES raw (sensor_msgs/Image mono8) |
      png (sensor_msgs/CompressedImage); GROUNDTRUTH pose | transform |
      odometry (the ASL ground truth as that message type)
  rosbag_interop.py read BAG
      checks each connection's md5sum against its definition, then prints
      one line per message: topic, type, header stamp [ns], then for
      images width, height and the adler32 of the decoded pixels, for IMU
      and poses their values (repr: exact doubles)

  rosbag_interop.py probe
      exits 0 when the packages it needs are installed

Exit status 77: the ROS Python packages are not installed (a skip).
"""
import struct
import sys
import zlib

try:
    import genpy
    import genpy.dynamic
    import rosbag
    from geometry_msgs.msg import PoseStamped, TransformStamped
    from nav_msgs.msg import Odometry
    from sensor_msgs.msg import CompressedImage, Image, Imu
except ImportError as e:
    print("skipped: %s (apt-get install python3-rosbag python3-sensor-msgs python3-nav-msgs)" % e)
    sys.exit(77)


def decode_gray_png(data):
    """(width, height, pixels) of an 8-bit greyscale, non-interlaced PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour == 0 and interlace == 0, "only 8-bit grey PNGs"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    out, prev = bytearray(), bytearray(width)
    for y in range(height):
        kind, row = raw[y * (width + 1)], bytearray(raw[y * (width + 1) + 1:(y + 1) * (width + 1)])
        for x in range(width):
            a = row[x - 1] if x else 0
            b, c = prev[x], (prev[x - 1] if x else 0)
            if kind == 1:
                row[x] = (row[x] + a) & 255
            elif kind == 2:
                row[x] = (row[x] + b) & 255
            elif kind == 3:
                row[x] = (row[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[x] = (row[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += row
        prev = row
    return width, height, bytes(out)


def csv_rows(path):
    with open(path) as f:
        return [line.strip().split(",") for line in f if line.strip() and not line.startswith("#")]


def stamp(ns):
    return genpy.Time(int(ns) // 1000000000, int(ns) % 1000000000)


def image_message(path, ns, frame, images):
    with open(path, "rb") as f:
        data = f.read()
    if images == "png":
        m = CompressedImage(format="png", data=data)
    else:
        width, height, pixels = decode_gray_png(data)
        m = Image(height=height, width=width, encoding="mono8", is_bigendian=0, step=width, data=pixels)
    m.header.stamp, m.header.frame_id = stamp(ns), frame
    return m


def groundtruth_message(row, kind):
    p, q = [float(v) for v in row[1:4]], [float(v) for v in row[4:8]]  # q: w, x, y, z
    if kind == "transform":
        m = TransformStamped(child_frame_id="body")
        t, r = m.transform.translation, m.transform.rotation
    else:
        m = PoseStamped() if kind == "pose" else Odometry(child_frame_id="body")
        pose = m.pose if kind == "pose" else m.pose.pose
        t, r = pose.position, pose.orientation
    t.x, t.y, t.z = p
    r.w, r.x, r.y, r.z = q
    m.header.stamp, m.header.frame_id = stamp(row[0]), "world"
    return m


def write(folder, out, compression, images, groundtruth):
    mav0 = folder + "/mav0"
    messages = []  # (time ns, topic, message)
    for cam in (0, 1):
        for ns, name in csv_rows("%s/cam%d/data.csv" % (mav0, cam)):
            path = "%s/cam%d/data/%s" % (mav0, cam, name)
            messages.append((int(ns), "/cam%d/image_raw" % cam, image_message(path, ns, "cam%d" % cam, images)))
    for row in csv_rows(mav0 + "/imu0/data.csv"):
        m = Imu()
        m.header.stamp, m.header.frame_id = stamp(row[0]), "imu0"
        v = [float(x) for x in row[1:7]]
        m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z = v[0:3]
        m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z = v[3:6]
        messages.append((int(row[0]), "/imu0", m))
    for row in csv_rows(mav0 + "/state_groundtruth_estimate0/data.csv"):
        messages.append((int(row[0]), "/groundtruth", groundtruth_message(row, groundtruth)))
    messages.sort(key=lambda m: m[0])
    with rosbag.Bag(out, "w", compression=compression, chunk_threshold=16 * 1024) as bag:
        for ns, topic, m in messages:
            bag.write(topic, m, t=stamp(ns))


def read(path):
    with rosbag.Bag(path) as bag:
        # Each connection's md5sum is the one ROS computes from the definition it carries.
        for c in bag._connections.values():
            generated = genpy.dynamic.generate_dynamic(c.datatype, c.msg_def)[c.datatype]
            assert generated._md5sum == c.md5sum, "%s: md5sum %s, its definition gives %s" % (c.topic, c.md5sum, generated._md5sum)
        for topic, m, _ in bag.read_messages():
            ns = m.header.stamp.secs * 1000000000 + m.header.stamp.nsecs
            fields = [topic, m._type, str(ns)]
            if m._type == "sensor_msgs/Image":
                assert m.encoding == "mono8" and m.step == m.width, "mono8 rows without padding"
                fields += [str(m.width), str(m.height), str(zlib.adler32(bytes(m.data)))]
            elif m._type == "sensor_msgs/CompressedImage":
                width, height, pixels = decode_gray_png(bytes(m.data))
                fields += [str(width), str(height), str(zlib.adler32(pixels))]
            elif m._type == "sensor_msgs/Imu":
                w, a = m.angular_velocity, m.linear_acceleration
                fields += [repr(v) for v in (w.x, w.y, w.z, a.x, a.y, a.z)]
            elif m._type == "geometry_msgs/PoseStamped":
                p, q = m.pose.position, m.pose.orientation
                fields += [repr(v) for v in (p.x, p.y, p.z, q.w, q.x, q.y, q.z)]
            print(" ".join(fields))


if __name__ == "__main__":
    if len(sys.argv) == 7 and sys.argv[1] == "write":
        write(*sys.argv[2:])
    elif len(sys.argv) == 2 and sys.argv[1] == "probe":
        pass  # the imports worked
    elif len(sys.argv) == 3 and sys.argv[1] == "read":
        read(sys.argv[2])
    else:
        sys.exit(__doc__)
