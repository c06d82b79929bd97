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

    def test_step_rate_is_a_frequency_status_against_the_rate(self):
        """Running, the step rate is measured against ~rate (60 Hz) with its tolerance, and
        OK; paused again, it reads "paused" at OK, never ERROR."""
        self.assertTrue(self.sim.pause(False).success)
        deadline = time.time() + 30.0
        while True:
            status = self.status('Step rate')
            self.assertNotEqual(status.level, DiagnosticStatus.ERROR, status.message)
            if 'steps per second' in status.message:
                break
            self.assertLess(time.time(), deadline, 'no measured step rate: ' + status.message)
        self.assertEqual(status.level, DiagnosticStatus.OK, status.message)
        self.assertIn('of 60.0 steps per second', status.message)
        values = {v.key: v.value for v in status.values}
        self.assertEqual(float(values['minimum acceptable rate (Hz)']), 54.0)
        self.assertGreater(int(values['steps in window']), 10)
        self.assertGreater(float(values['measured step rate (Hz)']), 54.0)
        self.assertTrue(self.sim.pause(True).success)
        self.status('Step rate')  # one that may have been taken before the pause
        paused = self.status('Step rate')
        self.assertEqual(paused.level, DiagnosticStatus.OK)
        self.assertEqual(paused.message, 'paused')


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'diagnostics', DiagnosticsTest, sys.argv)
