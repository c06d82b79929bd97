#!/usr/bin/env python3
"""Publishing happens off the stepping thread (rostest: test/publish_thread.test): with ~markers
and ~particles subscribed on 10,000 falling grains, whole messages arrive, and ~stats reports both
halves of a frame: the world thread's copy (frame_cost) and the publishing thread's messages
(publish_cost, zero until that thread has published a frame). How the two costs compare is a
performance figure, measured by the benchmark bench/node/frame_publish_bench.cpp (node_bench), not
asserted here: this test prints the medians it saw."""
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
    def test_the_frame_is_copied_and_published_apart(self):
        rospy.init_node('publish_thread_test')
        cond = threading.Condition()
        stats = []
        markers = [0]
        particles = []

        def on_stats(msg):
            with cond:
                if not msg.paused and msg.publish_cost > 0.0:
                    stats.append(msg)
                cond.notify_all()

        def on_markers(_):
            with cond:
                markers[0] += 1
                cond.notify_all()

        def on_particles(msg):
            with cond:
                particles.append(len(msg.particles))
                cond.notify_all()

        rospy.Subscriber(NS + '/markers', MarkerArray, on_markers, queue_size=5)
        rospy.Subscriber(NS + '/particles', ParticleArray, on_particles, queue_size=5)
        rospy.Subscriber(NS + '/stats', SimStats, on_stats, queue_size=50)
        deadline = time.time() + 40.0
        with cond:
            # Skip the first frames (the subscription reaching the node), then take 60 (2 s).
            while ((len(stats) < 90 or markers[0] <= 10 or not particles)
                   and time.time() < deadline):
                cond.wait(1.0)
        self.assertGreaterEqual(len(stats), 90, 'too few ~stats messages with a publish_cost')
        self.assertGreater(markers[0], 10, 'no ~markers arrived')
        self.assertTrue(particles, 'no ~particles arrived')
        self.assertEqual(set(particles), {10000}, 'a ~particles message without every grain')
        sample = stats[30:]
        self.assertTrue(all(m.particles == 10000 for m in sample))
        self.assertTrue(all(m.frame_cost > 0.0 for m in sample),
                        'a ~stats message without the world thread\'s frame_cost')
        publish = statistics.median(m.publish_cost for m in sample)
        frame = statistics.median(m.frame_cost for m in sample)
        sys.stdout.write('[ publish ] publishing thread %.3f ms a frame, world thread %.3f ms\n'
                         % (1e3 * publish, 1e3 * frame))


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'publish_thread', PublishThreadTest, sys.argv)
