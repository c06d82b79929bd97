#!/usr/bin/env python3
"""The ~step action and the ~step service's limit (rostest: test/step_action.test)."""
import os
import sys
import time
import unittest

import actionlib
import rospkg
import rospy
import rostest

from mass_aggregate_sim.msg import StepAction, StepGoal
from sim_client import SimClient

PUBLISH_RATE = 20.0
LONG = 100000  # steps: minutes of work on this scene, never finished within the test


class StepActionTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('step_action_test')
        cls.sim = SimClient()
        cls.action = actionlib.SimpleActionClient('/mass_aggregate_sim/step', StepAction)
        assert cls.action.wait_for_server(rospy.Duration(30.0))

    def setUp(self):
        self.sim.restart()

    def wait_for(self, condition, timeout, what):
        deadline = time.time() + timeout
        while not condition():
            self.assertLess(time.time(), deadline, 'timed out waiting for ' + what)
            time.sleep(0.02)

    def cancel_and_wait(self):
        self.action.cancel_goal()
        self.assertTrue(self.action.wait_for_result(rospy.Duration(30.0)))
        return self.action.get_state(), self.action.get_result()

    def test_feedback_stats_and_services_while_a_long_step_runs(self):
        start = self.sim.stats()
        feedback = []
        arrived = []

        def on_feedback(msg):
            feedback.append(msg)
            arrived.append(time.time())
        self.action.send_goal(StepGoal(steps=LONG), feedback_cb=on_feedback)
        self.wait_for(lambda: len(feedback) >= 3, 30.0, 'feedback from the ~step action')
        self.assertGreater(feedback[-1].steps_done, feedback[0].steps_done)
        self.assertEqual(feedback[-1].step, start.step + feedback[-1].steps_done)
        # ~stats keeps ~publish_rate (half of it on a loaded machine at least) during the run.
        counted = self.sim._count['stats']
        begun = time.time()
        time.sleep(3.0)
        rate = (self.sim._count['stats'] - counted) / (time.time() - begun)
        self.assertGreater(rate, 0.5 * PUBLISH_RATE)
        # Other services answer during the run, applied at a step boundary of it.
        begun = time.time()
        answer = self.sim.pause(True)
        self.assertTrue(answer.success, answer.message)
        self.assertLess(time.time() - begun, 5.0)
        self.assertEqual(self.action.get_state(), actionlib.GoalStatus.ACTIVE)
        # The service cannot start a second run meanwhile, and says why.
        refused = self.sim.step(5)
        self.assertFalse(refused.success)
        self.assertIn('another step run is under way', refused.message)
        # Feedback came at ~publish_rate (half of it on a loaded machine at least) over the run,
        # not only at its start.
        last = time.time()
        rate = (len(arrived) - 1) / (last - arrived[0])
        self.assertGreater(rate, 0.5 * PUBLISH_RATE, '%d feedbacks in %.1f s'
                           % (len(arrived), last - arrived[0]))
        self.assertGreater(arrived[-1], last - 1.0)  # still arriving at the end
        state, result = self.cancel_and_wait()
        self.assertEqual(state, actionlib.GoalStatus.PREEMPTED)
        self.assertGreater(result.steps_done, feedback[-1].steps_done - 1)
        self.assertLess(result.steps_done, LONG)
        self.assertEqual(result.step, start.step + result.steps_done)
        # The state it stopped in is the one published, at a step boundary.
        stats = self.sim.stats()
        self.assertEqual(stats.step, result.step)
        self.assertEqual(stats.state_hash, result.state_hash)

    def test_a_cancelled_run_leaves_a_deterministic_state(self):
        feedback = []
        self.action.send_goal(StepGoal(steps=LONG), feedback_cb=feedback.append)
        self.wait_for(lambda: feedback, 30.0, 'feedback')
        _, cancelled = self.cancel_and_wait()
        # The same number of steps from the same start, through the service in pieces, gives the
        # same state.
        self.sim.restart()
        left = cancelled.steps_done
        answer = None
        while left > 0:
            answer = self.sim.step(min(left, 1000))
            self.assertTrue(answer.success, answer.message)
            left -= min(left, 1000)
        self.assertEqual(answer.step, cancelled.step)
        self.assertEqual(answer.state_hash, cancelled.state_hash)

    def test_goals_are_refused_with_the_reason(self):
        self.assertTrue(self.sim.pause(False).success)
        self.action.send_goal(StepGoal(steps=10))
        self.assertTrue(self.action.wait_for_result(rospy.Duration(30.0)))
        self.assertEqual(self.action.get_state(), actionlib.GoalStatus.ABORTED)
        self.assertIn('pause it first', self.action.get_result().message)
        self.assertTrue(self.sim.pause(True).success)
        self.action.send_goal(StepGoal(steps=0))
        self.assertTrue(self.action.wait_for_result(rospy.Duration(30.0)))
        self.assertEqual(self.action.get_state(), actionlib.GoalStatus.ABORTED)
        self.assertIn('steps must be in [1, 100000]', self.action.get_result().message)
        self.action.send_goal(StepGoal(steps=25))
        self.assertTrue(self.action.wait_for_result(rospy.Duration(60.0)))
        self.assertEqual(self.action.get_state(), actionlib.GoalStatus.SUCCEEDED)
        self.assertEqual(self.action.get_result().steps_done, 25)

    def test_the_service_is_for_short_runs_and_points_to_the_action(self):
        answer = self.sim.step(1001)
        self.assertFalse(answer.success)
        self.assertIn('~max_service_steps', answer.message)
        self.assertIn('~step action', answer.message)
        self.assertTrue(self.sim.step(1000).success)

    def test_the_startup_line_names_the_scene_and_where_it_came_from(self):
        """It goes through rosconsole: rosout writes it to rosout.log."""
        log = os.path.join(rospkg.get_log_dir(), rospy.get_param('/run_id'), 'rosout.log')
        expected = "scene 'granular_pile' from the parameter /mass_aggregate_sim/scene"
        found = []

        def contains():
            if os.path.exists(log):
                with open(log, errors='replace') as f:
                    found[:] = [line for line in f if expected in line]
            return bool(found)
        self.wait_for(contains, 30.0, expected + ' in ' + log)


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'step_action', StepActionTest, sys.argv)
