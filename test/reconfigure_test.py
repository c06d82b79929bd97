#!/usr/bin/env python3
"""The dynamic_reconfigure server of the node (rostest: test/reconfigure.test); that a bag of the
changes replays to the same hash is in test/replay_test.py."""
import sys
import threading
import time
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from rosgraph_msgs.msg import Log
from std_msgs.msg import String

from mass_aggregate_sim.msg import Command
from sim_client import SimClient

NS = '/mass_aggregate_sim'


class ReconfigureTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('reconfigure_test')
        cls.sim = SimClient()
        cls.client = Client(NS, timeout=30.0)
        cls.cond = threading.Condition()
        cls.commands = []
        cls.configuration = []
        rospy.Subscriber(NS + '/commands', Command, cls.on, cls.commands, queue_size=100)
        rospy.Subscriber(NS + '/configuration', String, cls.on, cls.configuration, queue_size=10)
        # The node's own log messages (no rosout node needed: every node publishes on /rosout).
        cls.logs = []
        rosout = rospy.Subscriber('/rosout', Log, cls.on, cls.logs, queue_size=1000)
        deadline = time.time() + 20.0
        while rosout.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.05)

    @classmethod
    def on(cls, msg, into):
        with cls.cond:
            into.append(msg)
            cls.cond.notify_all()

    def wait(self, condition, what, timeout=20.0):
        with self.cond:
            self.assertTrue(self.cond.wait_for(condition, timeout), 'timed out: ' + what)

    def test_1_the_server_starts_from_what_runs(self):
        """The scene says 240 Hz and velocity_verlet; the parameter server and the reconfigure
        server say so too."""
        config = self.client.get_configuration(timeout=20.0)
        self.assertAlmostEqual(config['rate'], 240.0)
        self.assertEqual(config['integrator'], 'velocity_verlet')
        self.assertTrue(config['paused'])
        self.assertEqual(rospy.get_param(NS + '/integrator'), 'velocity_verlet')
        self.assertAlmostEqual(rospy.get_param(NS + '/rate'), 240.0)

    def test_2_live_change_is_applied_recorded_and_reflected(self):
        before = self.sim.stats()
        config = self.client.update_configuration({'integrator': 'rk4', 'gravity_z': -3.0,
                                                   'substeps': 2, 'body_iterations': 3,
                                                   'body_sleep': False})
        self.assertEqual(config['integrator'], 'rk4')
        self.assertEqual(config['body_iterations'], 3)
        self.assertFalse(config['body_sleep'])
        self.assertEqual(rospy.get_param(NS + '/body_iterations'), 3)
        self.assertAlmostEqual(config['gravity_z'], -3.0)
        self.assertEqual(rospy.get_param(NS + '/integrator'), 'rk4')
        self.assertEqual(rospy.get_param(NS + '/substeps'), 2)
        self.assertEqual(rospy.get_param(NS + '/gravity'), [0.0, 0.0, -3.0])
        self.wait(lambda: any(c.service == 'reconfigure' for c in self.commands),
                  'a reconfigure on ~commands')
        recorded = [c for c in self.commands if c.service == 'reconfigure'][-1]
        self.assertEqual(recorded.step, before.step)
        self.assertIn('integrator: velocity_verlet', recorded.configuration)
        self.wait(lambda: self.configuration and 'integrator: rk4' in
                  self.configuration[-1].data, '~configuration with rk4')
        self.assertIn('substeps: 2', self.configuration[-1].data)
        self.assertIn('body_iterations: 3', self.configuration[-1].data)
        self.assertIn('body_sleep: false', self.configuration[-1].data)
        self.assertIn('gravity: [0, 0, -3]', self.configuration[-1].data)
        # The world steps with them: a free particle falls at 3 m/s^2.
        spawned = self.sim.spawn([self.particle()])
        self.assertTrue(spawned.success, spawned.message)
        self.assertTrue(self.sim.step(240).success)
        fallen = self.sim.particle(spawned.ids[0])
        self.assertAlmostEqual(fallen.velocity.z, -3.0, places=6)

    def test_3_bad_values_are_refused_and_nothing_changes(self):
        before = self.client.get_configuration(timeout=20.0)
        stats = self.sim.stats()
        # Each refusal's reason reaches /rosout as the node's WARN, naming the parameter.
        for bad, reason in (({'integrator': 'leapfrog'}, "integrator: unknown integrator 'leapfrog'"),
                            ({'gravity_x': float('nan')}, 'gravity: must be finite'),
                            ({'divergence_policy': 'explode'},
                             "divergence_policy: unknown policy 'explode'")):
            config = self.client.update_configuration(bad)
            for key in ('integrator', 'gravity_x', 'divergence_policy', 'rate', 'substeps'):
                self.assertEqual(str(config[key]), str(before[key]), key)
            self.wait(lambda: any(
                log.level == Log.WARN and log.name == NS and
                'reconfigure refused, nothing changed: ' + reason in log.msg
                for log in self.logs), 'a WARN on /rosout with ' + reason)
        self.assertEqual(rospy.get_param(NS + '/integrator'), before['integrator'])
        after = self.sim.stats()
        self.assertEqual(after.state_hash, stats.state_hash)

    def test_4_a_pause_shows_on_the_parameter_server(self):
        self.assertTrue(self.sim.pause(False).success)
        self.assertFalse(rospy.get_param(NS + '/paused'))
        self.assertFalse(self.client.get_configuration(timeout=20.0)['paused'])
        config = self.client.update_configuration({'paused': True})
        self.assertTrue(config['paused'])
        self.assertTrue(self.sim.stats().paused)
        self.wait(lambda: self.commands and self.commands[-1].service == 'pause',
                  'the pause recorded')

    @staticmethod
    def particle():
        from sim_client import spec
        return spec('probe', (0.0, 5.0, 10.0))


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'reconfigure', ReconfigureTest, sys.argv)
