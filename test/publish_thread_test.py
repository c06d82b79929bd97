#!/usr/bin/env python3
"""Publishing happens off the stepping thread (rostest: test/publish_thread.test): with ~markers
and ~particles subscribed on 10,000 falling grains, the world thread's part of a published frame
(~stats frame_cost: copying the arrays into the frame, the energies) stays a fraction of what the
publishing thread spends building and sending the messages (~stats publish_cost). Publishing from
the world thread again would put that cost on frame_cost, or leave publish_cost near zero."""
import statistics
import sys
import threading
import time
import unittest

import rospy
import rostest
from visualization_msgs.msg import MarkerArray

from mass_aggregate_sim.msg import ParticleArray, SimStats

NS = '/mass_aggregate_sim'


class PublishThreadTest(unittest.TestCase):
    def test_the_world_thread_only_copies_the_frame(self):
        rospy.init_node('publish_thread_test')
        cond = threading.Condition()
        stats = []
        markers = [0]

        def on_stats(msg):
            with cond:
                if not msg.paused and msg.publish_cost > 0.0:
                    stats.append(msg)
                cond.notify_all()

        def on_markers(_):
            with cond:
                markers[0] += 1

        rospy.Subscriber(NS + '/markers', MarkerArray, on_markers, queue_size=5)
        rospy.Subscriber(NS + '/particles', ParticleArray, lambda _: None, queue_size=5)
        rospy.Subscriber(NS + '/stats', SimStats, on_stats, queue_size=50)
        deadline = time.time() + 40.0
        with cond:
            # Skip the first frames (the subscription reaching the node), then take 60 (2 s).
            while len(stats) < 90 and time.time() < deadline:
                cond.wait(1.0)
        self.assertGreaterEqual(len(stats), 90, 'too few ~stats messages')
        self.assertGreater(markers[0], 10, 'no ~markers arrived')
        sample = stats[30:]
        publish = statistics.median(m.publish_cost for m in sample)
        frame = statistics.median(m.frame_cost for m in sample)
        rospy.loginfo('publish_cost median %.3f ms, frame_cost median %.3f ms', 1e3 * publish,
                      1e3 * frame)
        sys.stdout.write('[ publish ] publishing thread %.3f ms a frame, world thread %.3f ms\n'
                         % (1e3 * publish, 1e3 * frame))
        self.assertGreater(publish, 1e-4, 'the publishing thread does no work')
        # Measured here: 1.13 ms against 0.25 ms; on the world thread the two would be one cost.
        self.assertLess(frame, publish / 2.0,
                        'the world thread spends %.3f ms on a frame the publishing thread '
                        'builds in %.3f ms' % (1e3 * frame, 1e3 * publish))


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'publish_thread', PublishThreadTest, sys.argv)
