#!/usr/bin/python3
"""Measures what the ROS graph costs per scan: CPU time of each of its processes (from /proc,
before and after the bag) and the latency from a scan's arrival to its /aft_mapped_to_init, with
the stages as nodes or as nodelets; and, over a long bag, the memory of each process as the bag
plays and the scans that were not mapped.

  source .ws/devel/setup.bash
  /usr/bin/python3 scripts/graph_cost.py --bag results/sim.bag --sensor kitti [--nodelets]
      [--rate 0.25] [--memory-every 500] [--skip 2] [--map DIR]

Prints one line per process (CPU ms per scan) and the total, the scans mapped, the latency's median
and 95th percentile (ms) over the first and the last 500 scans, and with --memory-every N the
resident memory (MB) of each process every N scans. With --skip N the CPU is counted from the
moment the Nth scan is mapped (a short bag's first pair, registered from several start guesses,
and start-up work would weigh on every scan; play it slowly, e.g. --rate 0.5, so that the moment
falls between two scans). With --map DIR the graph localizes on that saved map instead of
mapping. Starts its own roscore, the graph (use_sim_time
off: the scans' stamps are the bag's) and rosbag play; at --rate 0.25 nothing is dropped.
"""

import argparse
import os
import signal
import struct
import subprocess
import sys
import threading
import time

import rosbag
import rospy
from nav_msgs.msg import Odometry

CLOCK_TICKS = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid):
    """utime + stime of a process (s), or None when it is gone."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            fields = stat.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / CLOCK_TICKS
    except (FileNotFoundError, ProcessLookupError):
        return None


def graph_processes():
    """pid -> name of the stage processes (the nodes, or the nodelet graph's managers)."""
    found = {}
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                command = f.read().split(b"\0")
        except (FileNotFoundError, ProcessLookupError):
            continue
        text = [c.decode(errors="replace") for c in command if c]
        if not text:
            continue
        program = os.path.basename(text[0])
        names = [a.split(":=", 1)[1] for a in text if a.startswith("__name:=")]
        if program in ("image_projection", "feature_association", "map_optimization",
                       "transform_fusion", "graph_manager") and names:
            found[int(pid)] = names[0]
    return found


def resident_mb(pid):
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
    except (FileNotFoundError, ProcessLookupError):
        pass
    return None


class Latency:
    """Wall time from a scan's arrival to its mapped pose's, per stamp."""

    def __init__(self):
        self.arrived = {}
        self.latencies = []
        self.scans = 0
        self.lock = threading.Lock()
        rospy.Subscriber("/velodyne_points", rospy.AnyMsg, self.on_scan, queue_size=100)
        rospy.Subscriber("/aft_mapped_to_init", Odometry, self.on_mapped, queue_size=100)

    def on_scan(self, msg):
        # std_msgs/Header starts the message: seq, stamp.secs, stamp.nsecs (uint32 each).
        _, secs, nsecs = struct.unpack_from("<III", msg._buff, 0)
        with self.lock:
            self.arrived[(secs, nsecs)] = time.monotonic()
            self.scans += 1

    def on_mapped(self, msg):
        key = (msg.header.stamp.secs, msg.header.stamp.nsecs)
        with self.lock:
            if key in self.arrived:
                self.latencies.append(1000.0 * (time.monotonic() - self.arrived.pop(key)))


def percentile(values, share):
    values = sorted(values)
    return values[min(len(values) - 1, max(0, int(round(share * len(values))) - 1))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bag", required=True)
    parser.add_argument("--sensor", default="kitti")
    parser.add_argument("--nodelets", action="store_true")
    parser.add_argument("--rate", type=float, default=0.25)
    parser.add_argument("--memory-every", type=int, default=0,
                        help="print each process's resident memory every this many scans")
    parser.add_argument("--skip", type=int, default=0,
                        help="count the CPU from the moment this many scans are mapped")
    parser.add_argument("--map", default="", help="localize on this saved map (save_map's folder)")
    args = parser.parse_args()
    if args.map and not os.path.isfile(os.path.join(args.map, "map.yaml")):
        sys.exit(f"graph_cost: --map {args.map}: no map.yaml there (a folder save_map wrote)")
    scans = rosbag.Bag(args.bag).get_message_count("/velodyne_points")
    env = dict(os.environ)
    core = subprocess.Popen(["roscore"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    time.sleep(3)
    graph = subprocess.Popen(
        ["roslaunch", "adaptive_lego_loam", "nodes.launch", f"sensor:={args.sensor}",
         f"nodelets:={'true' if args.nodelets else 'false'}"]
        + ([f"map:={os.path.abspath(args.map)}"] if args.map else []),
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, start_new_session=True)
    try:
        rospy.init_node("graph_cost", anonymous=True, disable_signals=True)
        latency = Latency()
        time.sleep(6)
        processes = graph_processes()
        before = {pid: cpu_seconds(pid) for pid in processes}
        counted_scans = scans
        player = subprocess.Popen(["rosbag", "play", "-q", "-d", "2", "-r", str(args.rate),
                                   args.bag])
        memory = []  # (scans played, {name: MB})
        next_sample = 0
        while player.poll() is None:
            waiting_to_count = args.skip and counted_scans == scans
            mapped = len(latency.latencies)
            if waiting_to_count and args.skip <= mapped < scans:
                before = {pid: cpu_seconds(pid) for pid in processes}
                counted_scans = scans - mapped
                waiting_to_count = False
            if args.memory_every and latency.scans >= next_sample:
                memory.append((latency.scans, {name: resident_mb(pid)
                                               for pid, name in processes.items()}))
                next_sample += args.memory_every
            time.sleep(0.005 if waiting_to_count else 0.2)
        time.sleep(3)
        if args.memory_every:
            memory.append((latency.scans, {name: resident_mb(pid)
                                           for pid, name in processes.items()}))
        after = {pid: cpu_seconds(pid) for pid in processes}
        total = 0.0
        print(f"{'nodelets' if args.nodelets else 'nodes'}: {scans} scans, CPU ms per scan"
              f"{f' over the last {counted_scans}' if counted_scans < scans else ''}:")
        for pid, name in sorted(processes.items(), key=lambda item: item[1]):
            if before[pid] is None or after[pid] is None:
                continue
            ms = 1000.0 * (after[pid] - before[pid]) / counted_scans
            total += ms
            print(f"  {name:24s} {ms:7.1f}")
        print(f"  {'total':24s} {total:7.1f}")
        print(f"scans mapped: {len(latency.latencies)} of {scans}")
        for label, part in (("first", latency.latencies[:500]), ("last", latency.latencies[-500:])):
            if part:
                print(f"latency to /aft_mapped_to_init, {label} {len(part)} scans (ms): median "
                      f"{percentile(part, 0.5):.1f}, p95 {percentile(part, 0.95):.1f}, "
                      f"max {max(part):.1f}")
        for played, sizes in memory:
            print(f"memory after {played:5d} scans (MB): " +
                  ", ".join(f"{name} {mb:.0f}" for name, mb in sorted(sizes.items())
                            if mb is not None))
    finally:
        for process in (graph, core):
            os.killpg(process.pid, signal.SIGINT)
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
    return 0


if __name__ == "__main__":
    sys.exit(main())
