#!/usr/bin/env python3
"""Under /use_sim_time, paused and running, with or without /clock: a request naming an unknown
frame (particle and body services, joints and queries) is refused at once with a message naming
the frame, and the node goes on answering
(rostest: test/frame_lookup_clock.test, test/frame_lookup_no_clock.test). Every wait here is on
wall time: ROS time may stand still."""
import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Vector3
from std_srvs.srv import SetBool

from mass_aggregate_sim.msg import JointEndSpec
from mass_aggregate_sim.srv import (AddBodySpring, AddBodySpringRequest, AddForceField,
                                    AddForceFieldRequest, AddJoint,
                                    AddJointRequest, ApplyBodyImpulse,
                                    ApplyBodyImpulseRequest, ApplyBodyWrench,
                                    ApplyBodyWrenchRequest, ApplyForce, ApplyForceRequest,
                                    GetBodyState, GetBodyStateRequest, Overlap, OverlapRequest,
                                    Raycast, RaycastRequest, SetBodyState, SetBodyStateRequest,
                                    SetState, SetStateRequest, Spawn, SpawnBody, Step)
from sim_client import body, end, spec

NS = '/mass_aggregate_sim'
# A hung call must fail the test, not the time limit; an answer is expected in milliseconds (the
# node answers within 100 ms), the margin is for a loaded machine.
ANSWER_WITHIN = 5.0


def call(proxy, *args):
    """(answer, wall seconds), or (None, ANSWER_WITHIN) when no answer came in time."""
    result = {}

    def run():
        result['answer'] = proxy(*args)
    begun = time.time()
    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(ANSWER_WITHIN)
    return result.get('answer'), time.time() - begun


class FrameLookupTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('frame_lookup_test')
        for name in ('spawn', 'set_state', 'apply_force', 'pause', 'step', 'spawn_body',
                     'add_joint', 'overlap'):
            rospy.wait_for_service(NS + '/' + name, timeout=30.0)
        # Persistent: the refusals are timed without the master's lookup of the service.
        cls.spawn = rospy.ServiceProxy(NS + '/spawn', Spawn, persistent=True)
        cls.set_state = rospy.ServiceProxy(NS + '/set_state', SetState, persistent=True)
        cls.apply_force = rospy.ServiceProxy(NS + '/apply_force', ApplyForce, persistent=True)
        cls.body_services = [
            (rospy.ServiceProxy(NS + '/' + name, srv, persistent=True), request)
            for name, srv, request in [
                ('spawn_body', SpawnBody, [body('b', frame_id='nowhere')]),
                ('set_body_state', SetBodyState, SetBodyStateRequest(
                    name='crate', reference_frame='nowhere', set_pose=True,
                    pose=body().pose)),
                ('get_body_state', GetBodyState, GetBodyStateRequest(
                    name='crate', reference_frame='nowhere')),
                ('apply_body_wrench', ApplyBodyWrench, ApplyBodyWrenchRequest(
                    name='crate', reference_frame='nowhere')),
                ('apply_body_impulse', ApplyBodyImpulse, ApplyBodyImpulseRequest(
                    name='crate', reference_frame='nowhere')),
                ('add_joint', AddJoint, AddJointRequest(
                    type='ball', a=end(JointEndSpec.BODY, 'crate'), frame_id='nowhere')),
                ('add_body_spring', AddBodySpring, AddBodySpringRequest(
                    type='spring', a=end(JointEndSpec.BODY, 'crate'), frame_id='nowhere',
                    stiffness=1.0, rest_length=-1.0)),
                ('add_force_field', AddForceField, AddForceFieldRequest(
                    type='buoyancy', body_names=['crate'], liquid_density=1000.0,
                    frame_id='nowhere')),
                ('raycast', Raycast, RaycastRequest(
                    frame_id='nowhere', direction=Vector3(1.0, 0.0, 0.0), max_distance=1.0)),
                ('overlap', Overlap, OverlapRequest(
                    frame_id='nowhere', shape=OverlapRequest.SPHERE, radius=1.0,
                    pose=body().pose))]]
        cls.pause = rospy.ServiceProxy(NS + '/pause', SetBool)
        cls.step = rospy.ServiceProxy(NS + '/step', Step)

    def refused_at_once(self, proxy, request):
        answer, took = call(proxy, request)
        self.assertIsNotNone(answer, 'no answer within %.0f s' % ANSWER_WITHIN)
        self.assertFalse(answer.success)
        self.assertIn("unknown frame 'nowhere'", answer.message)
        # Refused without waiting, every time: a lookup with a timeout would take 500 ms or
        # never answer.
        self.assertLess(took, 0.1, 'refused in %.0f ms' % (1e3 * took))
        return took

    def still_answers(self, paused):
        answer, _ = call(self.pause, paused)
        self.assertIsNotNone(answer, '~pause did not answer')
        self.assertTrue(answer.success, answer.message)
        if paused:
            answer, _ = call(self.step, 3)
            self.assertIsNotNone(answer, '~step did not answer')
            self.assertTrue(answer.success, answer.message)

    def requests(self):
        force = ApplyForceRequest(name='ball', frame_id='nowhere', force=Vector3(1.0, 0.0, 0.0),
                                  mode=ApplyForceRequest.ONE_STEP)
        state = SetStateRequest(name='ball', frame_id='nowhere', set_position=True)
        return [(self.spawn, [spec('p', (0.0, 0.0, 2.0), frame_id='nowhere')]),
                (self.set_state, state), (self.apply_force, force)] + self.body_services

    def check(self, paused):
        answer, _ = call(self.pause, paused)
        self.assertIsNotNone(answer)
        took = [self.refused_at_once(proxy, request) for proxy, request in self.requests()]
        self.still_answers(True)
        self.still_answers(paused)
        sys.stderr.write('[ frame_lookup ] paused=%s: refused in %s ms\n'
                         % (paused, ', '.join('%.1f' % (1e3 * t) for t in took)))

    def test_paused(self):
        self.check(True)

    def test_running(self):
        self.check(False)


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'frame_lookup', FrameLookupTest, sys.argv)
