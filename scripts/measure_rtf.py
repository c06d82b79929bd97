#!/usr/bin/env python3
"""Measures a running mass_aggregate_sim node: subscribes to ~markers (so the node builds and
publishes them) and averages ~stats over a wall-clock window.

Usage: measure_rtf.py [--node /mass_aggregate_sim] [--duration 10] [--warmup 2]
Prints particles, real-time factor (simulated s / wall s over the window), mean step cost,
overruns during the window, contacts, marker messages received per second and their size.
"""
import argparse
import sys
import time

import rospy
from visualization_msgs.msg import MarkerArray

from mass_aggregate_sim.msg import SimStats


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--node', default='/mass_aggregate_sim')
    parser.add_argument('--duration', type=float, default=10.0)
    parser.add_argument('--warmup', type=float, default=2.0)
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node('measure_rtf', anonymous=True)
    markers = {'count': 0, 'points': 0}

    def on_markers(msg):
        markers['count'] += 1
        markers['points'] = sum(len(m.points) for m in msg.markers)

    stats = []
    rospy.Subscriber(args.node + '/markers', MarkerArray, on_markers, queue_size=1,
                     buff_size=2 ** 26)
    rospy.Subscriber(args.node + '/stats', SimStats, stats.append, queue_size=100)
    time.sleep(args.warmup)
    del stats[:]
    markers['count'] = 0
    start = time.time()
    time.sleep(args.duration)
    wall = time.time() - start
    window = list(stats)
    if len(window) < 2:
        print('no ~stats received: is the node running (and not paused)?')
        return 1
    first, last = window[0], window[-1]
    sim = last.time - first.time
    cost = sum(s.step_cost_mean for s in window[1:]) / (len(window) - 1)
    publish = sum(s.publish_cost for s in window[1:]) / (len(window) - 1)
    # The world thread's copy of each frame (nodes that publish from the stepping thread have none).
    frame = sum(getattr(s, 'frame_cost', 0.0) for s in window[1:]) / (len(window) - 1)
    print('particles %d, window %.1f s wall: real-time factor %.3f (sim %.2f s), step cost mean '
          '%.3f ms (max %.3f ms), publish cost mean %.3f ms, frame copy mean %.3f ms, overruns %d, '
          'contacts %d, '
          'iterations %d, markers %.1f Hz (%d points)'
          % (last.particles, wall, sim / wall, sim, 1e3 * cost,
             1e3 * max(s.step_cost_max for s in window), 1e3 * publish, 1e3 * frame,
             last.overruns - first.overruns,
             last.contacts, last.resolver_iterations, markers['count'] / wall,
             markers['points']))
    return 0


if __name__ == '__main__':
    sys.exit(main())
