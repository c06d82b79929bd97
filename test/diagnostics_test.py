#!/usr/bin/env python3
"""/diagnostics from diagnostic_updater: every status is there, and a divergent scene turns the
stability status to ERROR (rostest: test/diagnostics.test)."""
import sys
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus

from sim_client import SimClient

PREFIX = 'mass_aggregate_sim: '
NAMES = ['Step rate', 'Step cost', 'Stability', 'Contacts', 'Capacity']


class DiagnosticsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('diagnostics_test')
        cls.sim = SimClient()
        cls.cond = threading.Condition()
        cls.arrays = []
        rospy.Subscriber('/diagnostics', DiagnosticArray, cls.on_array, queue_size=10)

    @classmethod
    def on_array(cls, msg):
        with cls.cond:
            cls.arrays.append(msg)
            cls.cond.notify_all()

    def status(self, name, timeout=30.0):
        """The named status from an array published from now on."""
        with self.cond:
            seen = len(self.arrays)
            deadline = time.time() + timeout
            while True:
                for array in self.arrays[seen:]:
                    for status in array.status:
                        if status.name == PREFIX + name:
                            return status
                seen = len(self.arrays)
                left = deadline - time.time()
                self.assertGreater(left, 0.0, 'no %s status on /diagnostics' % name)
                self.cond.wait(left)

    def test_divergence_turns_stability_to_error(self):
        for name in NAMES:
            self.assertIsNotNone(self.status(name))
        paused = self.status('Step rate')
        self.assertEqual(paused.level, DiagnosticStatus.OK)
        self.assertEqual(paused.message, 'paused')
        before = self.status('Stability')
        self.assertEqual(before.level, DiagnosticStatus.WARN, before.message)
        answer = self.sim.step(200)
        self.assertTrue(answer.success, answer.message)
        self.assertGreater(self.sim.stats().divergence_events, 0)
        after = self.status('Stability')
        self.assertEqual(after.level, DiagnosticStatus.ERROR, after.message)
        self.assertIn('divergence', after.message)
        values = {v.key: v.value for v in after.values}
        self.assertNotEqual(values['divergence events'], '0')


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'diagnostics', DiagnosticsTest, sys.argv)
