#!/usr/bin/env python3
"""Bodies and joints through the node's real services and topics (rostest:
test/body_services.test): analytic impulses and wrenches, in the world and in a turned frame, a
DURATION wrench's exact step count, a hinged pendulum's period, ~joint_states with a motor changed
at runtime, a body spring and buoyancy added at runtime, ~contacts, ~bodies, /tf, queries, and
hostile requests refused with nothing changed."""
import math
import sys
import threading
import time
import unittest

import rospy
from diagnostic_msgs.msg import DiagnosticArray
import rostest
import tf2_ros
from geometry_msgs.msg import Point, TransformStamped, Vector3
from sensor_msgs.msg import JointState
from visualization_msgs.msg import Marker, MarkerArray

from mass_aggregate_sim.msg import (BodyContact, BodyContactArray, BodySpec, Command,
                                    JointEndSpec)
from mass_aggregate_sim.srv import (AddBodySpringRequest, AddForceFieldRequest, AddJointRequest,
                                    ApplyBodyImpulseRequest, ApplyBodyWrenchRequest,
                                    GetBodyStateRequest, OverlapRequest, RaycastRequest,
                                    RaycastResponse, SetBodyStateRequest, SetHingeMotorRequest)
from sim_client import SimClient, body, end, shape, spec

DT = 0.01
G = 9.81
NAN, INF = float('nan'), float('inf')


def vec(x, y, z):
    return Vector3(x, y, z)


def point(x, y, z):
    return Point(x, y, z)


def impulse(name, j=(0.0, 0.0, 0.0), at=(0.0, 0.0, 0.0), angular=(0.0, 0.0, 0.0), frame=''):
    return ApplyBodyImpulseRequest(name=name, reference_frame=frame, reference_point=point(*at),
                                   impulse=vec(*j), angular_impulse=vec(*angular))


def wrench(name, force=(0.0, 0.0, 0.0), torque=(0.0, 0.0, 0.0), at=(0.0, 0.0, 0.0),
           mode=ApplyBodyWrenchRequest.ONE_STEP, duration=0.0, frame=''):
    r = ApplyBodyWrenchRequest(name=name, reference_frame=frame, reference_point=point(*at),
                               mode=mode, duration=duration)
    r.wrench.force, r.wrench.torque = vec(*force), vec(*torque)
    return r


def hinge(a, b, anchor, axis, name='', motor=False, speed=0.0, torque=0.0, frame=''):
    return AddJointRequest(type='hinge', name=name, a=a, b=b, frame_id=frame,
                           anchor=point(*anchor), axis=vec(*axis), motor=motor,
                           motor_speed=speed, max_motor_torque=torque, min_length=-1.0,
                           max_length=-1.0)


def xyz(v):
    return (v.x, v.y, v.z)


class Latest:
    """The latest message of a topic, and a count to wait for fresh ones."""

    def __init__(self, topic, kind):
        self.cond = threading.Condition()
        self.msg, self.count = None, 0
        self.sub = rospy.Subscriber(topic, kind, self._on, queue_size=5)

    def _on(self, msg):
        with self.cond:
            self.msg, self.count = msg, self.count + 1
            self.cond.notify_all()

    def fresh(self, count=2, timeout=10.0):
        with self.cond:
            target = self.count + count
            assert self.cond.wait_for(lambda: self.count >= target, timeout), 'no message'
            return self.msg


class BodyServicesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('body_services_test')
        cls.sim = SimClient()
        # 'tilted' at (1, 2, 3), turned 90 degrees about z.
        cls.tf = tf2_ros.StaticTransformBroadcaster()
        t = TransformStamped()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id = 'world'
        t.child_frame_id = 'tilted'
        t.transform.translation = vec(1.0, 2.0, 3.0)
        t.transform.rotation.z = math.sqrt(0.5)
        t.transform.rotation.w = math.sqrt(0.5)
        cls.tf.sendTransform(t)
        cls.buffer = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.buffer)
        cls.buffer.lookup_transform('world', 'tilted', rospy.Time(0), rospy.Duration(10.0))
        cls.commands = []
        cls.command_sub = rospy.Subscriber('/mass_aggregate_sim/commands', Command,
                                           cls.commands.append, queue_size=1000)

    def setUp(self):
        self.sim.restart()

    def spawn(self, *bodies):
        answer = self.sim.spawn_body(list(bodies))
        self.assertTrue(answer.success, answer.message)
        return answer.ids

    def state(self, name, frame=''):
        answer = self.sim.get_body_state(GetBodyStateRequest(name=name, reference_frame=frame))
        self.assertTrue(answer.success, answer.message)
        return answer

    def assertVec(self, v, expected, tol=1e-9, what=''):
        for got, want in zip(xyz(v), expected):
            self.assertAlmostEqual(got, want, delta=tol, msg='%s: %s != %s' % (what, xyz(v),
                                                                             expected))

    def test_impulse_on_a_unit_cube_is_analytic(self):
        self.spawn(body('cube'))
        # J = (0, 1, 0) N s at (0.5, 0, 0) on 1 kg, I = 1/6: dv = 1 m/s, dw = (0, 0, 3) rad/s.
        answer = self.sim.apply_body_impulse(impulse('cube', (0.0, 1.0, 0.0), (0.5, 0.0, 0.0)))
        self.assertTrue(answer.success, answer.message)
        self.assertVec(answer.twist.linear, (0.0, 1.0, 0.0), what='dv')
        self.assertVec(answer.twist.angular, (0.0, 0.0, 3.0), what='dw')
        s = self.state('cube')
        self.assertVec(s.twist.linear, (0.0, 1.0, 0.0))
        self.assertVec(s.twist.angular, (0.0, 0.0, 3.0))
        self.assertEqual(s.header.frame_id, 'world')
        self.assertGreater(s.header.stamp.to_sec(), 0.0)

    def test_the_same_impulse_in_a_turned_frame_gives_the_turned_result(self):
        self.spawn(body('turned', frame_id='tilted'))
        s = self.state('turned')
        self.assertVec(s.pose.position, (1.0, 2.0, 3.0))
        self.assertAlmostEqual(s.pose.orientation.z, math.sqrt(0.5), delta=1e-12)
        answer = self.sim.apply_body_impulse(
            impulse('turned', (0.0, 1.0, 0.0), (0.5, 0.0, 0.0), frame='tilted'))
        self.assertTrue(answer.success, answer.message)
        # Answered in the request's frame: the cube's own result.
        self.assertVec(answer.twist.linear, (0.0, 1.0, 0.0))
        self.assertVec(answer.twist.angular, (0.0, 0.0, 3.0))
        # In the world: turned 90 degrees about z.
        s = self.state('turned')
        self.assertVec(s.twist.linear, (-1.0, 0.0, 0.0))
        self.assertVec(s.twist.angular, (0.0, 0.0, 3.0))
        # A wrench in the turned frame is turned too (gazebo_ros #310 applied it unturned).
        self.spawn(body('pushed', x=(0.0, 30.0, 0.0)))
        answer = self.sim.apply_body_wrench(wrench('pushed', force=(1.0, 0.0, 0.0), frame='tilted'))
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(answer.steps, 1)
        self.assertTrue(self.sim.step(1).success)
        s = self.state('pushed')
        self.assertVec(s.twist.linear, (0.0, DT, -G * DT), tol=1e-12)

    def test_a_two_second_duration_wrench_lasts_exactly_round_t_over_dt_steps(self):
        self.spawn(body('sled', mass=2.0))
        answer = self.sim.apply_body_wrench(
            wrench('sled', force=(3.0, 0.0, 0.0), mode=ApplyBodyWrenchRequest.DURATION,
                   duration=2.0))
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(answer.steps, round(2.0 / DT))
        self.assertTrue(self.sim.step(199).success)
        self.assertEqual(self.sim.stats().sustained_forces, 1)
        self.assertTrue(self.sim.step(1).success)
        self.assertEqual(self.sim.stats().sustained_forces, 0)
        self.assertTrue(self.sim.step(50).success)
        # 200 steps of 3 N on 2 kg: 3 m/s, not a step more or less.
        self.assertAlmostEqual(self.state('sled').twist.linear.x, 3.0 * 2.0 / 2.0, delta=1e-9)

    def test_a_hinged_pendulum_swings_with_the_physical_pendulum_period(self):
        r, d, theta0 = 0.1, 1.0, 0.05
        pivot = (0.0, 20.0, 10.0)
        bob = body('bob', x=(pivot[0] + d * math.sin(theta0), pivot[1],
                             pivot[2] - d * math.cos(theta0)),
                   shapes=[shape('sphere', radius=r)])
        bob.never_sleep = True
        self.spawn(bob)
        joint = self.sim.add_joint(hinge(end(JointEndSpec.BODY, 'bob'), end(), pivot,
                                         (0.0, 1.0, 0.0), name='pivot'))
        self.assertTrue(joint.success, joint.message)
        expected = 2.0 * math.pi * math.sqrt((0.4 * r * r + d * d) / (G * d))
        crossings = []
        last_x, t = self.state('bob').pose.position.x - pivot[0], 0.0
        while len(crossings) < 4 and t < 10.0:
            self.assertTrue(self.sim.step(2).success)
            s = self.state('bob')
            x = s.pose.position.x - pivot[0]
            if last_x > 0.0 >= x:  # crossing the bottom towards -x: once a period
                crossings.append(s.time - 2 * DT * x / (x - last_x))
            last_x = x
            t = s.time
        self.assertEqual(len(crossings), 4)
        period = (crossings[-1] - crossings[0]) / 3.0
        sys.stderr.write('[ pendulum ] period %.5f s, expected %.5f s (%.3f %%)\n'
                         % (period, expected, 100.0 * (period / expected - 1.0)))
        self.assertLess(abs(period / expected - 1.0), 0.005)

    def test_joint_states_follow_a_motor_changed_at_runtime(self):
        states = Latest('/mass_aggregate_sim/joint_states', JointState)
        self.spawn(body('wheel', x=(0.0, -20.0, 0.0), shapes=[shape('box', (0.5, 0.5, 0.1))]))
        joint = self.sim.add_joint(hinge(end(), end(JointEndSpec.BODY, 'wheel'),
                                         (0.0, -20.0, 0.0), (0.0, 0.0, 1.0), name='axle',
                                         motor=True, speed=2.0, torque=100.0))
        self.assertTrue(joint.success, joint.message)
        self.assertTrue(self.sim.step(100).success)
        msg = states.fresh()
        self.assertEqual(list(msg.name), ['axle'])
        self.assertAlmostEqual(msg.velocity[0], 2.0, delta=0.01)
        changed = self.sim.set_hinge_motor(SetHingeMotorRequest(name='axle', enabled=True,
                                                                speed=-1.0, max_torque=100.0))
        self.assertTrue(changed.success, changed.message)
        self.assertTrue(self.sim.step(100).success)
        self.assertAlmostEqual(states.fresh().velocity[0], -1.0, delta=0.01)
        states.sub.unregister()

    def test_a_body_spring_added_at_runtime_holds_a_body_at_its_stretch(self):
        # 2 kg on k = 100 N/m, critically damped (c = 2 sqrt(k m) = 28.3 N s/m), from the spring's
        # rest length: it settles m g / k = 0.1962 m lower. Then ~remove_link drops it.
        m, k = 2.0, 100.0
        top = (0.0, 30.0, 10.0)
        self.spawn(body('hung', x=(top[0], top[1], top[2] - 1.0), mass=m,
                        shapes=[shape('sphere', radius=0.1)]))
        request = AddBodySpringRequest(type='spring', a=end(JointEndSpec.BODY, 'hung'), b=end(),
                                       anchor=point(top[0], top[1], top[2] - 1.0),
                                       anchor_b=point(*top), stiffness=k,
                                       damping=2.0 * math.sqrt(k * m), rest_length=-1.0)
        refused = self.sim.add_body_spring(AddBodySpringRequest(
            type='coil', a=request.a, b=request.b, stiffness=k, rest_length=-1.0))
        self.assertFalse(refused.success)
        self.assertIn('spring, bungee', refused.message)
        elsewhere = self.sim.add_body_spring(AddBodySpringRequest(
            type='spring', a=request.a, b=request.b, frame_id='no_such_frame', stiffness=k,
            rest_length=-1.0))
        self.assertFalse(elsewhere.success)
        self.assertIn('frame_id', elsewhere.message)
        added = self.sim.add_body_spring(request)
        self.assertTrue(added.success, added.message)
        self.assertTrue(self.sim.step(500).success)
        z = self.state('hung').pose.position.z
        sys.stderr.write('[ body spring ] rests %.5f m below its rest length (m g / k = %.5f)\n'
                         % (top[2] - 1.0 - z, m * G / k))
        self.assertAlmostEqual(top[2] - 1.0 - z, m * G / k, delta=1e-3)
        removed = self.sim.remove_link(link_id=added.link_id)
        self.assertTrue(removed.success, removed.message)
        self.assertTrue(self.sim.step(10).success)
        self.assertLess(self.state('hung').twist.linear.z, -0.5)

    def test_a_plank_given_buoyancy_at_runtime_floats_level(self):
        # A 2 x 2 x 0.4 m plank of half the water's density (800 kg) let go tilted 20 degrees
        # about x, in water whose surface is z' = 0.5 of the 'tilted' frame (z = 3.5 in the
        # world): it rights itself and floats half under, its centre at the surface. Then
        # ~remove_force_field takes the water away and it falls.
        half_turn = math.radians(20.0) / 2.0
        plank = body('plank', x=(40.0, 0.0, 3.5),
                     q=(math.sin(half_turn), 0.0, 0.0, math.cos(half_turn)), mass=800.0,
                     shapes=[shape('box', (1.0, 1.0, 0.2))])
        plank.never_sleep = True
        self.spawn(plank)
        water = AddForceFieldRequest(type='buoyancy', body_names=['plank'],
                                     liquid_density=1000.0, surface_height=0.5, frame_id='tilted')
        floats = self.sim.add_force_field(water)
        self.assertTrue(floats.success, floats.message)
        self.assertEqual(len(floats.force_ids), 1)
        drag = self.sim.add_force_field(AddForceFieldRequest(
            type='drag', body_names=['plank'], k1=6000.0, angular=2000.0, frame_id='tilted'))
        self.assertTrue(drag.success, drag.message)
        # Both recorded in the world (a replay needs no tf): the water's surface moved, the
        # drag's frame dropped too.
        deadline = time.time() + 10.0
        while len([c for c in self.commands if c.service == 'add_force_field']) < 2:
            self.assertLess(time.time(), deadline, 'add_force_field not on ~commands')
            time.sleep(0.05)
        fields = []
        for c in self.commands:
            if c.service == 'add_force_field':
                fields.append(AddForceFieldRequest())
                fields[-1].deserialize(bytes(c.request))
        self.assertEqual([(f.type, f.frame_id) for f in fields[-2:]],
                         [('buoyancy', ''), ('drag', '')])
        self.assertAlmostEqual(fields[-2].surface_height, 3.5, delta=1e-12)
        self.assertVec(fields[-2].up, (0.0, 0.0, 1.0), tol=1e-12)
        self.assertTrue(self.sim.step(1000).success)
        settled = self.state('plank')
        q = settled.pose.orientation
        tilt = math.degrees(2.0 * math.asin(min(1.0, math.sqrt(q.x * q.x + q.y * q.y))))
        sys.stderr.write('[ buoyancy ] plank at z %.5f (surface 3.5), tilted %.4f degrees\n'
                         % (settled.pose.position.z, tilt))
        self.assertAlmostEqual(settled.pose.position.z, 3.5, delta=1e-3)
        self.assertLess(tilt, 0.1)
        removed = self.sim.remove_force_field(force_id=floats.force_ids[0])
        self.assertTrue(removed.success, removed.message)
        again = self.sim.remove_force_field(force_id=floats.force_ids[0])
        self.assertFalse(again.success)
        self.assertIn('no drag or buoyancy', again.message)
        self.assertTrue(self.sim.step(20).success)
        self.assertLess(self.state('plank').twist.linear.z, -0.5)

    def test_states_relative_to_another_body(self):
        self.spawn(body('base', x=(0.0, 40.0, 0.0), q=(0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5))),
                   body('rider', x=(1.0, 40.0, 0.0)))
        s = self.state('rider', 'base')
        # base's x is the world's y: rider sits 1 m along -y of base's frame.
        self.assertVec(s.pose.position, (0.0, -1.0, 0.0), tol=1e-12)
        self.assertEqual(s.header.frame_id, 'base')
        # Teleport relative to base: 2 m along base's x, i.e. world +y.
        answer = self.sim.set_body_state(SetBodyStateRequest(
            name='rider', reference_frame='base', set_pose=True,
            pose=body(x=(2.0, 0.0, 0.0)).pose))
        self.assertTrue(answer.success, answer.message)
        self.assertVec(self.state('rider').pose.position, (0.0, 42.0, 0.0), tol=1e-12)
        # A spinning reference: still relative to it means moving with it.
        spin = self.sim.set_body_state(SetBodyStateRequest(
            name='base', set_twist=True, twist=body(w=(0.0, 0.0, 1.0)).twist))
        self.assertTrue(spin.success, spin.message)
        still = self.sim.set_body_state(SetBodyStateRequest(
            name='rider', reference_frame='base', set_twist=True, twist=body().twist))
        self.assertTrue(still.success, still.message)
        s = self.state('rider')
        self.assertVec(s.twist.linear, (-2.0, 0.0, 0.0), tol=1e-12)  # w x r = z x 2y
        self.assertVec(s.twist.angular, (0.0, 0.0, 1.0), tol=1e-12)

    def test_reset_brings_bodies_back_still(self):
        """A reset zeroes velocities as well as poses (gazebo's reset_world left them)."""
        start = self.state('drifter')
        self.spawn(body('thrown', v=(5.0, 0.0, 0.0), w=(0.0, 1.0, 0.0)))
        moved = self.sim.set_body_state(SetBodyStateRequest(
            name='drifter', set_pose=True, pose=body(x=(-12.0, 1.0, 0.0)).pose, set_twist=True,
            twist=body(v=(1.0, 2.0, 3.0), w=(0.5, 0.0, 0.0)).twist))
        self.assertTrue(moved.success, moved.message)
        self.assertTrue(self.sim.apply_body_wrench(wrench(
            'drifter', force=(1.0, 0.0, 0.0), mode=ApplyBodyWrenchRequest.UNTIL_CLEARED)).success)
        self.assertTrue(self.sim.step(10).success)
        self.assertTrue(self.sim.reset().success)
        names = sorted(b.name for b in self.sim.fresh('bodies').bodies)
        self.assertEqual(names, ['anvil', 'drifter'])
        drifter = self.state('drifter')
        self.assertEqual(drifter.pose, start.pose)
        self.assertVec(drifter.twist.linear, (0.0, 0.0, 0.0), tol=0.0)
        self.assertVec(drifter.twist.angular, (0.0, 0.0, 0.0), tol=0.0)
        self.assertEqual(self.sim.stats().sustained_forces, 0)

    def test_spawn_at_the_limits(self):
        """Every bound reached exactly is accepted, up to ~max_bodies (20) bodies; one more is
        refused."""
        q = (0.0, 0.0, 0.0, 1.0 + 0.9e-6)  # |q| within 1e-6 of 1
        specs = [
            body('far', x=(1e6, -1e6, 1e6), q=q, mass=1e9,
                 shapes=[shape('box', (1e3, 1e3, 1e3))]),
            body('light', x=(-1e6, 1e6, -1e6), mass=1e-6, shapes=[shape('sphere', radius=1e-4)]),
            body('fast', x=(100.0, 0.0, 0.0), v=(1e5, -1e5, 1e5), w=(1e4, 0.0, 0.0),
                 shapes=[shape('sphere', radius=0.1)]),
            body('compound', x=(200.0, 0.0, 0.0),
                 shapes=[shape('sphere', radius=0.1, at=(1e3, 0.0, 0.0))] +
                 [shape('capsule', radius=0.1, half_length=0.2)] * 63),
        ]
        specs += [body('filler_%d' % i, x=(300.0 + 2.0 * i, 0.0, 0.0)) for i in range(14)]
        answer = self.sim.spawn_body(specs)
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(self.sim.stats().bodies, 20)
        refused = self.sim.spawn_body([body('one_more', x=(0.0, -50.0, 0.0))])
        self.assertFalse(refused.success)
        self.assertIn('~max_bodies', refused.message)

    def test_removing_a_body_takes_its_joints(self):
        self.spawn(body('left', x=(0.0, 60.0, 0.0)), body('right', x=(2.0, 60.0, 0.0)))
        joint = self.sim.add_joint(hinge(end(JointEndSpec.BODY, 'left'),
                                         end(JointEndSpec.BODY, 'right'), (1.0, 60.0, 0.0),
                                         (0.0, 1.0, 0.0)))
        self.assertTrue(joint.success, joint.message)
        self.assertEqual(self.sim.stats().joints, 1)
        removed = self.sim.remove_body([], ['right'])
        self.assertTrue(removed.success, removed.message)
        self.assertEqual(removed.joints_removed, 1)
        stats = self.sim.stats()
        self.assertEqual((stats.bodies, stats.joints), (3, 0))  # with the anvil and the drifter
        self.assertFalse(self.sim.remove_joint(joint.joint_id).success)

    def test_bodies_topic_tf_and_markers(self):
        q = (0.0, 0.0, math.sin(0.25), math.cos(0.25))
        self.spawn(body('crate', x=(3.0, 4.0, 5.0), q=q, v=(1.0, 0.0, 0.0)))
        msg = self.sim.fresh('bodies')
        crate = [b for b in msg.bodies if b.name == 'crate'][0]
        self.assertVec(crate.pose.position, (3.0, 4.0, 5.0), tol=1e-12)
        self.assertVec(crate.twist.linear, (1.0, 0.0, 0.0), tol=1e-12)
        self.assertEqual(crate.type, BodySpec.DYNAMIC)
        self.assertEqual(msg.header.frame_id, 'world')
        t = self.buffer.lookup_transform('world', 'crate', rospy.Time(0), rospy.Duration(5.0))
        self.assertVec(t.transform.translation, (3.0, 4.0, 5.0), tol=1e-9)
        self.assertAlmostEqual(t.transform.rotation.z, q[2], delta=1e-9)
        arrays = Latest('/mass_aggregate_sim/markers', MarkerArray)
        markers = arrays.fresh()
        arrays.sub.unregister()
        bodies = [m for m in markers.markers if m.ns == 'bodies' and m.action == Marker.ADD]
        self.assertEqual(len(bodies), 3)  # the anvil, the drifter and the crate, one part each
        stats = self.sim.stats()
        self.assertEqual(stats.bodies, 3)

    def test_contacts_carry_the_weight_they_hold(self):
        contacts = Latest('/mass_aggregate_sim/contacts', BodyContactArray)
        load = body('load', x=(10.0, 0.0, 1.0), mass=3.0)
        load.never_sleep = True
        self.spawn(load)
        self.assertTrue(self.sim.step(100).success)
        msg = contacts.fresh()
        contacts.sub.unregister()
        found = [c for c in msg.contacts if {c.body_name, c.other_name} == {'load', 'anvil'}]
        self.assertEqual(len(found), 1, msg.contacts)
        c = found[0]
        self.assertEqual(c.other_kind, BodyContact.BODY)
        force = sum(p.normal_force for p in c.points)
        self.assertAlmostEqual(force, 3.0 * G, delta=0.05 * 3.0 * G)
        self.assertAlmostEqual(abs(c.normal.z), 1.0, delta=1e-6)
        stats = self.sim.stats()
        self.assertGreaterEqual(stats.body_contacts, 1)
        self.assertEqual(stats.islands, 2)  # the load (the anvil is fixed) and the drifter

    def test_sleeping_bodies_are_counted_on_stats_and_diagnostics(self):
        arrays = Latest('/diagnostics', DiagnosticArray)
        self.spawn(body('sleeper', x=(10.0, 0.0, 1.0), mass=2.0))
        # 1.5 s at 100 Hz: it lands on the anvil and is slow for more than 0.5 s.
        self.assertTrue(self.sim.step(150).success)
        stats = self.sim.stats()
        self.assertEqual(stats.bodies, 3)
        self.assertEqual(stats.sleeping_bodies, 1)
        # The first Capacity status made from a frame after the steps (it is updated once a
        # diagnostic period from the latest frame).
        capacity = None
        deadline = time.time() + 10.0
        while time.time() < deadline:
            for status in arrays.fresh(count=1).status:
                if status.name.endswith('Capacity'):
                    capacity = {kv.key: kv.value for kv in status.values}
            if capacity is not None and capacity.get('bodies') == '3':
                break
        arrays.sub.unregister()
        self.assertIsNotNone(capacity, 'no Capacity status on /diagnostics')
        self.assertEqual(capacity['bodies'], '3')
        self.assertEqual(capacity['sleeping bodies'], '1')
        self.assertEqual(capacity['islands'], '2')  # the sleeper (the anvil is fixed), the drifter

    def test_queries_return_bodies_and_particles(self):
        ray = self.sim.raycast(RaycastRequest(origin=point(10.0, 0.0, 5.0),
                                              direction=vec(0.0, 0.0, -2.0), max_distance=10.0))
        self.assertTrue(ray.success, ray.message)
        self.assertTrue(ray.hit)
        self.assertEqual((ray.kind, ray.name), (RaycastResponse.BODY, 'anvil'))
        self.assertAlmostEqual(ray.distance, 4.5, delta=1e-9)
        self.assertVec(ray.normal, (0.0, 0.0, 1.0), tol=1e-9)
        # In the tilted frame: the bead at world (0, 5, 0) is at tilted (3, 1, -3).
        ray = self.sim.raycast(RaycastRequest(frame_id='tilted', origin=point(3.0, 1.0, 0.0),
                                              direction=vec(0.0, 0.0, -1.0), max_distance=10.0))
        self.assertTrue(ray.success, ray.message)
        self.assertEqual((ray.hit, ray.name), (True, 'bead'))
        self.assertVec(ray.point, (3.0, 1.0, -2.95), tol=1e-9)
        sphere = self.sim.overlap(OverlapRequest(shape=OverlapRequest.SPHERE, radius=6.0,
                                                 pose=body(x=(5.0, 2.0, 0.0)).pose))
        self.assertTrue(sphere.success, sphere.message)
        self.assertEqual((list(sphere.body_names), list(sphere.particle_names)),
                         (['anvil'], ['bead']))
        # A thin box from (5, 0) to (0, 5), turned 135 degrees about z, reaches the bead at its
        # end; turned 45 degrees (the same axis-aligned bounds) it does not.
        for angle, found in ((0.75 * math.pi, ['bead']), (0.25 * math.pi, [])):
            box = self.sim.overlap(OverlapRequest(
                shape=OverlapRequest.BOX, half_extents=vec(3.6, 0.1, 0.1),
                pose=body(x=(2.5, 2.5, 0.0), q=(0.0, 0.0, math.sin(angle / 2),
                                                math.cos(angle / 2))).pose))
            self.assertTrue(box.success, box.message)
            self.assertEqual((list(box.body_names), list(box.particle_names)), ([], found))

    def test_hostile_requests_are_refused_and_change_nothing(self):
        self.spawn(body('target', x=(0.0, 0.0, 5.0)))
        joint = self.sim.add_joint(hinge(end(JointEndSpec.BODY, 'target'), end(),
                                         (0.0, 0.0, 6.0), (0.0, 1.0, 0.0)))
        self.assertTrue(joint.success, joint.message)
        before = self.sim.stats()
        huge = 'x' * 100000
        ok_shape = shape()
        body_cases = [
            ('NaN position', body('n', x=(NAN, 0.0, 0.0))),
            ('Inf position', body('n', x=(0.0, INF, 0.0))),
            ('beyond 1e6 m', body('n', x=(0.0, 0.0, 2e6))),
            ('zero quaternion', body('n', q=(0.0, 0.0, 0.0, 0.0))),
            ('non-unit quaternion', body('n', q=(0.0, 0.0, 0.0, 1.00001))),
            ('NaN quaternion', body('n', q=(NAN, 0.0, 0.0, 1.0))),
            ('NaN twist', body('n', v=(NAN, 0.0, 0.0))),
            ('Inf spin', body('n', w=(0.0, 0.0, INF))),
            ('zero size', body('n', shapes=[shape('box', (0.5, 0.0, 0.5))])),
            ('negative size', body('n', shapes=[shape('sphere', radius=-1.0)])),
            ('NaN size', body('n', shapes=[shape('capsule', radius=NAN, half_length=0.1)])),
            ('unknown shape', body('n', shapes=[shape('cone')])),
            ('no shapes', body('n', shapes=[])),
            ('absurd compound', body('n', shapes=[ok_shape] * 65)),
            ('shape far away', body('n', shapes=[shape(at=(5e3, 0.0, 0.0))])),
            ('shape zero quaternion', body('n', shapes=[shape(q=(0.0, 0.0, 0.0, 0.0))])),
            ('mass < 0', body('n', mass=-1.0)),
            ('mass NaN', body('n', mass=NAN)),
            ('density < 0', body('n', mass=0.0, shapes=[shape(density=-5.0)])),
            ('singular inertia', body('n', shapes=[shape('box', (1e3, 1e-4, 1e-4))])),
            ('friction NaN', body('n', shapes=[shape(friction=NAN)])),
            ('bad type', body('n', kind=7)),
            ('fixed with a velocity', body('n', kind=BodySpec.FIXED, v=(1.0, 0.0, 0.0))),
            ('taken by a body', body('target')),
            ('taken by a particle', body('bead')),
            ('the world frame', body('world')),
            ('unknown frame', body('n', frame_id='nowhere')),
            ('huge name', body(huge)),
            ('over max_bodies', None),
            ('quaternion just beyond 1e-6', body('n', q=(0.0, 0.0, 0.0, 1.0 + 1.1e-6))),
            ('size just below 1e-4', body('n', shapes=[shape('sphere', radius=0.99e-4)])),
            ('mass just above 1e9', body('n', mass=1.01e9)),
        ]
        refused = []
        for what, spec_ in body_cases:
            bodies = [body('m%d' % i) for i in range(20)] if spec_ is None else [spec_]
            refused.append(('spawn_body ' + what, self.sim.spawn_body(bodies)))
        refused.append(('spawn_body one good one bad',
                        self.sim.spawn_body([body('good'), body('bad', mass=-1.0)])))
        joint_cases = [
            ('unknown body', hinge(end(JointEndSpec.BODY, 'ghost'), end(), (0, 0, 0), (0, 1, 0))),
            ('unknown id', hinge(end(JointEndSpec.BODY, id=987654321), end(), (0, 0, 0),
                                 (0, 1, 0))),
            ('identical bodies', hinge(end(JointEndSpec.BODY, 'target'),
                                       end(JointEndSpec.BODY, 'target'), (0, 0, 0), (0, 1, 0))),
            ('zero axis', hinge(end(JointEndSpec.BODY, 'target'), end(), (0, 0, 6), (0, 0, 0))),
            ('NaN axis', hinge(end(JointEndSpec.BODY, 'target'), end(), (0, 0, 6), (NAN, 0, 0))),
            ('NaN anchor', hinge(end(JointEndSpec.BODY, 'target'), end(), (NAN, 0, 6),
                                 (0, 1, 0))),
            ('unknown frame', hinge(end(JointEndSpec.BODY, 'target'), end(), (0, 0, 6),
                                    (0, 1, 0), frame='nowhere')),
            ('bad end kind', hinge(end(9, 'target'), end(), (0, 0, 6), (0, 1, 0))),
            ('hinge to a particle', hinge(end(JointEndSpec.BODY, 'target'),
                                          end(JointEndSpec.PARTICLE, 'bead'), (0, 0, 6),
                                          (0, 1, 0))),
            ('fixed body to the world', hinge(end(JointEndSpec.BODY, 'anvil'), end(), (0, 0, 6),
                                              (0, 1, 0))),
            ('unknown type', AddJointRequest(type=huge, a=end(JointEndSpec.BODY, 'target'))),
        ]
        limits = hinge(end(JointEndSpec.BODY, 'target'), end(), (0, 0, 6), (0, 1, 0))
        limits.limit, limits.lower, limits.upper = True, 1.0, -1.0
        joint_cases.append(('lower > upper', limits))
        motor = hinge(end(JointEndSpec.BODY, 'target'), end(), (0, 0, 6), (0, 1, 0), motor=True,
                      speed=INF, torque=1.0)
        joint_cases.append(('Inf motor speed', motor))
        for what, request in joint_cases:
            refused.append(('add_joint ' + what, self.sim.add_joint(request)))

        def spring(**fields):
            r = AddBodySpringRequest(type='spring', a=end(JointEndSpec.BODY, 'target'), b=end(),
                                     anchor=point(0.0, 0.0, 5.0), anchor_b=point(0.0, 0.0, 7.0),
                                     stiffness=10.0, rest_length=-1.0)
            for name, value in fields.items():
                setattr(r, name, value)
            return r
        spring_cases = [
            ('unknown type', spring(type='coil')),
            ('two particles', spring(a=end(JointEndSpec.PARTICLE, 'bead'),
                                     b=end(JointEndSpec.PARTICLE, 'bead'))),
            ('fixed body to the world', spring(a=end(JointEndSpec.BODY, 'anvil'))),
            ('unknown body', spring(a=end(JointEndSpec.BODY, 'ghost'))),
            ('bad end kind', spring(b=end(9))),
            ('NaN stiffness', spring(stiffness=NAN)),
            ('negative damping', spring(damping=-1.0)),
            ('Inf rest length', spring(rest_length=INF)),
            ('NaN anchor', spring(anchor_b=point(NAN, 0.0, 0.0))),
            ('unknown frame', spring(frame_id='nowhere')),
        ]
        for what, request in spring_cases:
            refused.append(('add_body_spring ' + what, self.sim.add_body_spring(request)))

        def field(**fields):
            r = AddForceFieldRequest(type='buoyancy', body_names=['target'], liquid_density=1000.0)
            for name, value in fields.items():
                setattr(r, name, value)
            return r
        field_cases = [
            ('unknown type', field(type='wind')),
            ('no target', field(body_names=[])),
            ('unknown body after a good one', field(body_names=['target', 'ghost'])),
            ('unknown particle id', field(particle_ids=[987654321])),
            ('particle without a depth', field(body_names=[], particle_names=['bead'])),
            ('depth for the shapes model', field(max_depth=0.2)),
            ('unknown model', field(model='center')),
            ('NaN density', field(liquid_density=NAN)),
            ('NaN depth', field(max_depth=NAN)),
            ('Inf surface', field(surface_height=INF)),
            ('NaN up', field(up=vec(NAN, 0.0, 1.0))),
            ('negative drag', field(type='drag', k1=-1.0)),
            ('unknown frame', field(frame_id='nowhere')),
        ]
        for what, request in field_cases:
            refused.append(('add_force_field ' + what, self.sim.add_force_field(request)))
        refused.append(('remove_force_field unknown id',
                        self.sim.remove_force_field(force_id=987654)))
        refused += [
            ('impulse NaN', self.sim.apply_body_impulse(impulse('target', (NAN, 0.0, 0.0)))),
            ('impulse Inf point', self.sim.apply_body_impulse(
                impulse('target', (1.0, 0.0, 0.0), at=(INF, 0.0, 0.0)))),
            ('impulse on a fixed body', self.sim.apply_body_impulse(
                impulse('anvil', (1.0, 0.0, 0.0)))),
            ('impulse unknown body', self.sim.apply_body_impulse(impulse('ghost', (1, 0, 0)))),
            ('impulse unknown frame', self.sim.apply_body_impulse(
                impulse('target', (1.0, 0.0, 0.0), frame='nowhere'))),
            ('wrench NaN torque', self.sim.apply_body_wrench(wrench('target',
                                                                    torque=(0, NAN, 0)))),
            ('wrench bad mode', self.sim.apply_body_wrench(wrench('target', mode=9))),
            ('wrench negative duration', self.sim.apply_body_wrench(
                wrench('target', force=(1, 0, 0), mode=ApplyBodyWrenchRequest.DURATION,
                       duration=-1.0))),
            ('wrench NaN duration', self.sim.apply_body_wrench(
                wrench('target', force=(1, 0, 0), mode=ApplyBodyWrenchRequest.DURATION,
                       duration=NAN))),
            ('wrench nothing to clear', self.sim.apply_body_wrench(
                wrench('target', mode=ApplyBodyWrenchRequest.CLEAR))),
            ('wrench unknown frame', self.sim.apply_body_wrench(
                wrench('target', force=(1, 0, 0), frame=huge))),
            ('set_state zero quaternion', self.sim.set_body_state(SetBodyStateRequest(
                name='target', set_pose=True, pose=body(q=(0.0, 0.0, 0.0, 0.0)).pose))),
            ('set_state nothing', self.sim.set_body_state(SetBodyStateRequest(name='target'))),
            ('set_state fixed moving', self.sim.set_body_state(SetBodyStateRequest(
                name='anvil', set_twist=True, twist=body(v=(1.0, 0.0, 0.0)).twist))),
            ('get_state unknown', self.sim.get_body_state(GetBodyStateRequest(name=huge))),
            ('remove unknown body', self.sim.remove_body([], ['target', 'ghost'])),
            ('remove twice', self.sim.remove_body([], ['target', 'target'])),
            ('remove absurd count', self.sim.remove_body(list(range(21)), [])),
            ('remove unknown joint', self.sim.remove_joint(joint.joint_id + 100)),
            ('motor unknown joint', self.sim.set_hinge_motor(SetHingeMotorRequest(
                joint_id=joint.joint_id + 100, enabled=True))),
            ('motor negative torque', self.sim.set_hinge_motor(SetHingeMotorRequest(
                joint_id=joint.joint_id, enabled=True, max_torque=-1.0))),
            ('raycast zero direction', self.sim.raycast(RaycastRequest(max_distance=1.0))),
            ('raycast NaN origin', self.sim.raycast(RaycastRequest(
                origin=point(NAN, 0, 0), direction=vec(1, 0, 0), max_distance=1.0))),
            ('overlap zero radius', self.sim.overlap(OverlapRequest(
                shape=OverlapRequest.SPHERE, pose=body().pose))),
            ('overlap bad shape', self.sim.overlap(OverlapRequest(shape=5, pose=body().pose))),
            ('overlap zero quaternion box', self.sim.overlap(OverlapRequest(
                shape=OverlapRequest.BOX, half_extents=vec(1, 1, 1)))),
        ]
        for what, answer in refused:
            self.assertFalse(answer.success, what)
            self.assertTrue(answer.message, what + ': no message')
            self.assertLess(len(answer.message), 400, what + ': ' + answer.message[:400])
        after = self.sim.stats()
        self.assertEqual(after.state_hash, before.state_hash)
        self.assertEqual((after.bodies, after.joints, after.particles, after.sustained_forces),
                         (before.bodies, before.joints, before.particles,
                          before.sustained_forces))
        self.assertEqual(after.commands_applied, before.commands_applied)


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'body_services', BodyServicesTest, sys.argv)
