#!/usr/bin/env python3
"""Drives the node through its real services and topics (rostest: test/node_services.test)."""
import math
import sys
import time
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import TransformStamped, Vector3
from rosgraph_msgs.msg import Clock
from visualization_msgs.msg import Marker, MarkerArray

from mass_aggregate_sim.srv import AddLinkRequest, ApplyForceRequest, SetStateRequest
from sim_client import SimClient, spec

RATE = 100.0
DT = 1.0 / RATE
G = 9.81
SHOT_X0 = (0.0, 0.0, 1.5)
SHOT_V0 = (12.0, 0.0, 9.0)
MAX_PARTICLES = 50


def vec(x, y, z):
    v = Vector3()
    v.x, v.y, v.z = x, y, z
    return v


class NodeServicesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('node_services_test')
        cls.sim = SimClient()
        # A frame 'tilted' at (1, 2, 3), turned 90 degrees about z, for requests in another frame.
        cls.tf = tf2_ros.StaticTransformBroadcaster()
        t = TransformStamped()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id = 'world'
        t.child_frame_id = 'tilted'
        t.transform.translation = vec(1.0, 2.0, 3.0)
        t.transform.rotation.z = math.sqrt(0.5)
        t.transform.rotation.w = math.sqrt(0.5)
        cls.tf.sendTransform(t)

    def setUp(self):
        self.sim.restart()

    def spawn_one(self, **kwargs):
        answer = self.sim.spawn([spec(**kwargs)])
        self.assertTrue(answer.success, answer.message)
        return answer.ids[0]

    def test_spawn_then_read_back(self):
        answer = self.sim.spawn([spec('probe', (1.0, 2.0, 3.0), (0.5, -0.25, 0.0), mass=3.0,
                                      radius=0.2, damping=0.9)])
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(len(answer.ids), 1)
        p = self.sim.particle(answer.ids[0])
        self.assertIsNotNone(p)
        self.assertEqual(p.name, 'probe')
        self.assertEqual((p.position.x, p.position.y, p.position.z), (1.0, 2.0, 3.0))
        self.assertEqual((p.velocity.x, p.velocity.y, p.velocity.z), (0.5, -0.25, 0.0))
        self.assertEqual(p.mass, 3.0)
        self.assertEqual(p.radius, 0.2)

    def test_spawn_many_in_another_frame(self):
        answer = self.sim.spawn([spec('t1', (1.0, 0.0, 0.0), (1.0, 0.0, 0.0), frame_id='tilted'),
                                 spec('t2', (0.0, 0.0, 0.0), frame_id='world')])
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(len(answer.ids), 2)
        p = self.sim.particle(answer.ids[0])
        # (1, 2, 3) + Rz(90) (1, 0, 0) = (1, 3, 3); the velocity is only turned.
        self.assertAlmostEqual(p.position.x, 1.0, places=9)
        self.assertAlmostEqual(p.position.y, 3.0, places=9)
        self.assertAlmostEqual(p.position.z, 3.0, places=9)
        self.assertAlmostEqual(p.velocity.x, 0.0, places=9)
        self.assertAlmostEqual(p.velocity.y, 1.0, places=9)

    def test_impulse_changes_velocity_by_j_over_m(self):
        mass = 3.0
        pid = self.spawn_one(name='kicked', x=(0.0, 0.0, 5.0), mass=mass)
        impulse = (1.5, -0.3, 0.7)
        answer = self.sim.apply_impulse(pid, '', '', vec(*impulse))
        self.assertTrue(answer.success, answer.message)
        # Exactly J * (1 / m), the engine's own operation.
        expected = tuple(j * (1.0 / mass) for j in impulse)
        self.assertEqual((answer.velocity.x, answer.velocity.y, answer.velocity.z), expected)
        p = self.sim.particle(pid)
        self.assertEqual((p.velocity.x, p.velocity.y, p.velocity.z), expected)

    def test_projectile_lands_where_the_formula_says(self):
        # z(t) = z0 + vz t - g t^2 / 2 = 0
        t_land = (SHOT_V0[2] + math.sqrt(SHOT_V0[2] ** 2 + 2.0 * G * SHOT_X0[2])) / G
        steps = int(round(t_land / DT))
        answer = self.sim.step(steps)
        self.assertTrue(answer.success, answer.message)
        t = answer.time
        self.assertEqual(answer.step, steps)
        shot = [p for p in self.sim.fresh('particles').particles if p.name == 'shot'][0]
        z_exact = SHOT_X0[2] + SHOT_V0[2] * t - 0.5 * G * t * t
        x_exact = SHOT_X0[0] + SHOT_V0[0] * t
        # Semi-implicit Euler is first order: z_n - z(t_n) = -g dt t_n / 2.
        self.assertAlmostEqual(shot.position.x, x_exact, places=9)
        self.assertLessEqual(abs(shot.position.z - z_exact), 0.5 * G * DT * t * 1.0001)
        self.assertAlmostEqual(shot.position.z - z_exact, -0.5 * G * DT * t, places=6)
        # And it is on the ground there, within one step of travel.
        self.assertLess(abs(shot.position.z), abs(shot.velocity.z) * DT + 0.5 * G * DT * t)
        self.assertAlmostEqual(shot.position.x, SHOT_V0[0] * t_land, delta=SHOT_V0[0] * DT)

    def test_force_for_a_duration_gives_the_momentum(self):
        mass = 2.0
        pid = self.spawn_one(name='pushed', x=(0.0, 0.0, 10.0), mass=mass)
        force, duration = 3.0, 0.25
        answer = self.sim.apply_force(pid, '', '', vec(force, 0.0, 0.0),
                                      ApplyForceRequest.DURATION, duration)
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(answer.steps, 25)
        self.assertTrue(self.sim.step(40).success)
        p = self.sim.particle(pid)
        self.assertAlmostEqual(mass * p.velocity.x, force * duration, places=12)
        # Gravity acted for all 40 steps.
        self.assertAlmostEqual(mass * p.velocity.z, -mass * G * 40 * DT, places=9)

    def test_force_until_cleared_in_another_frame(self):
        pid = self.spawn_one(name='towed', x=(0.0, 0.0, 10.0), mass=1.0)
        answer = self.sim.apply_force(pid, '', 'tilted', vec(1.0, 0.0, 0.0),
                                      ApplyForceRequest.UNTIL_CLEARED, 0.0)
        self.assertTrue(answer.success, answer.message)
        self.assertTrue(self.sim.step(10).success)
        cleared = self.sim.apply_force(pid, '', '', vec(0.0, 0.0, 0.0), ApplyForceRequest.CLEAR,
                                       0.0)
        self.assertTrue(cleared.success, cleared.message)
        self.assertTrue(self.sim.step(10).success)
        p = self.sim.particle(pid)
        # The tilted frame's x is the world's y.
        self.assertAlmostEqual(p.velocity.y, 10 * DT, places=12)
        self.assertAlmostEqual(p.velocity.x, 0.0, places=12)

    def test_pause_step_reset_give_exact_times_and_states(self):
        start_hash = self.sim.stats().state_hash
        first = self.sim.step(7)
        self.assertTrue(first.success, first.message)
        self.assertEqual((first.step, first.time), (7, 7 * DT))
        second = self.sim.step(5)
        self.assertEqual((second.step, second.time), (12, 12 * DT))
        stats = self.sim.stats()
        self.assertTrue(stats.paused)
        self.assertEqual((stats.step, stats.state_hash), (12, second.state_hash))
        # Paused: time stands still.
        self.assertEqual(self.sim.stats().step, 12)

        self.assertTrue(self.sim.reset().success)
        stats = self.sim.stats()
        self.assertEqual((stats.step, stats.time, stats.state_hash), (0, 0.0, start_hash))
        again = self.sim.step(12)
        self.assertEqual(again.state_hash, second.state_hash)

        # Stepping is refused while running.
        self.assertTrue(self.sim.pause(False).success)
        refused = self.sim.step(1)
        self.assertFalse(refused.success)
        self.assertIn('pause it first', refused.message)
        self.assertTrue(self.sim.pause(True).success)

    def test_clock_follows_sim_time_and_never_goes_back(self):
        clocks = []
        sub = rospy.Subscriber('/clock', Clock, lambda msg: clocks.append(msg.clock.to_sec()))
        rospy.sleep(0.3)
        self.assertTrue(self.sim.step(30).success)
        self.assertTrue(self.sim.reset().success)
        self.assertTrue(self.sim.step(10).success)
        rospy.sleep(0.3)
        sub.unregister()
        self.assertGreater(len(clocks), 2)
        self.assertEqual(clocks, sorted(clocks))
        # After the reset the clock continues from where it was: +10 steps past the +30.
        self.assertGreaterEqual(clocks[-1] - clocks[0], 40 * DT - 1e-9)

    def test_stamps_are_ros_time_and_the_body_has_simulated_time(self):
        """Not on /use_sim_time here: stamps are wall time (tf consumers on wall time see
        current stamps), the simulated time is in the message body."""
        self.assertTrue(self.sim.step(50).success)
        stats = self.sim.stats()
        particles = self.sim.fresh('particles')
        now = time.time()
        for msg in (stats, particles):
            self.assertLess(abs(msg.header.stamp.to_sec() - now), 30.0)
            self.assertEqual(msg.step, 50)
            self.assertAlmostEqual(msg.time, 50 * DT)

    def test_a_refusal_quotes_at_most_100_characters(self):
        huge = 'x' * 100000
        for what, answer in [
                ('remove', self.sim.remove([], [huge])),
                ('link type', self.sim.add_link(AddLinkRequest(type=huge, a_name='shot',
                                                               to_anchor=True))),
                ('frame', self.sim.apply_impulse(0, 'shot', huge, vec(1.0, 0.0, 0.0))),
                ('set_state', self.sim.set_state(SetStateRequest(name=huge, set_velocity=True)))]:
            self.assertFalse(answer.success, what)
            self.assertLess(len(answer.message), 400, what + ': ' + answer.message[:400])

    def test_markers_show_particles_and_start_over_after_reset(self):
        arrays = []
        sub = rospy.Subscriber('/mass_aggregate_sim/markers', MarkerArray, arrays.append)
        deadline = time.time() + 5.0
        while not arrays and time.time() < deadline:
            time.sleep(0.05)
        self.assertTrue(arrays, 'no ~markers')
        self.spawn_one(name='big', x=(0.0, 0.0, 3.0), radius=0.7)
        self.sim.stats()
        self.sim.stats()
        spheres = [m for m in arrays[-1].markers
                   if m.ns == 'particles' and m.action == Marker.ADD]
        self.assertEqual(sorted(m.scale.x for m in spheres), [0.1, 1.4])  # one list per radius
        self.assertEqual(sum(len(m.points) for m in spheres), 2)
        del arrays[:]
        self.assertTrue(self.sim.reset().success)
        self.sim.stats()
        self.sim.stats()
        sub.unregister()
        resets = [a for a in arrays if a.markers and a.markers[0].action == Marker.DELETEALL]
        self.assertEqual(len(resets), 1)
        spheres = [m for m in resets[0].markers if m.ns == 'particles']
        self.assertEqual(sum(len(m.points) for m in spheres), 1)

    def test_collider_has_a_static_frame(self):
        buffer = tf2_ros.Buffer()
        listener = tf2_ros.TransformListener(buffer)
        t = buffer.lookup_transform('world', 'world/collider_1', rospy.Time(0),
                                    rospy.Duration(5.0))
        del listener
        p = t.transform.translation
        self.assertEqual((p.x, p.y, p.z), (0.0, 50.0, 0.0))

    def test_cables_and_rods_through_the_service(self):
        a = self.spawn_one(name='ca', x=(0.0, 0.0, 5.0))
        b = self.spawn_one(name='cb', x=(0.0, 0.0, 4.0))
        rod = self.sim.add_link(AddLinkRequest(type='rod', a=a, b=b, length=-1.0))
        self.assertTrue(rod.success, rod.message)
        cable = self.sim.add_link(AddLinkRequest(type='cable', a=a, to_anchor=True,
                                                 anchor=vec(0.0, 0.0, 6.0), max_length=1.0))
        self.assertTrue(cable.success, cable.message)
        self.assertTrue(self.sim.step(120).success)
        # Hanging: a stays 1 m below the anchor, b 1 m below a (within the resolver's tolerance).
        pa, pb = self.sim.particle(a), self.sim.particle(b)
        self.assertAlmostEqual(pa.position.z, 5.0, delta=1e-3)
        self.assertAlmostEqual(pa.position.z - pb.position.z, 1.0, delta=1e-3)
        self.assertTrue(self.sim.remove_link(rod.link_id).success)
        self.assertTrue(self.sim.remove_link(cable.link_id).success)

    def test_links_are_added_and_removed(self):
        a = self.spawn_one(name='la', x=(0.0, 0.0, 5.0))
        b = self.spawn_one(name='lb', x=(1.0, 0.0, 5.0))
        answer = self.sim.add_link(AddLinkRequest(type='spring', a=a, b=b, stiffness=10.0,
                                                  rest_length=-1.0, max_length=-1.0, length=-1.0))
        self.assertTrue(answer.success, answer.message)
        anchored = self.sim.add_link(AddLinkRequest(type='bungee', a_name='la', to_anchor=True,
                                                    stiffness=5.0, rest_length=0.5,
                                                    max_length=-1.0, length=-1.0))
        self.assertTrue(anchored.success, anchored.message)
        self.assertEqual(self.sim.stats().force_generators, 2)
        self.assertTrue(self.sim.remove_link(answer.link_id).success)
        self.assertFalse(self.sim.remove_link(answer.link_id).success)
        self.assertEqual(self.sim.stats().force_generators, 1)
        removed = self.sim.remove([], ['la'])
        self.assertTrue(removed.success, removed.message)
        self.assertEqual(self.sim.stats().force_generators, 0)  # the link went with it

    def test_bad_requests_are_refused_and_change_nothing(self):
        pid = self.spawn_one(name='target', x=(0.0, 0.0, 5.0), mass=2.0)
        before = self.sim.stats()
        nan, inf = float('nan'), float('inf')
        refused = [
            ('spawn NaN position', self.sim.spawn([spec('n', (0.0, nan, 0.0))])),
            ('spawn Inf velocity', self.sim.spawn([spec('n', v=(inf, 0.0, 0.0))])),
            ('spawn mass 0', self.sim.spawn([spec('n', mass=0.0)])),
            ('spawn mass < 0', self.sim.spawn([spec('n', mass=-1.0)])),
            ('spawn mass NaN', self.sim.spawn([spec('n', mass=nan)])),
            ('spawn mass Inf', self.sim.spawn([spec('n', mass=inf)])),
            ('spawn damping > 1', self.sim.spawn([spec('n', damping=2.0)])),
            ('spawn one good one bad', self.sim.spawn([spec('ok'), spec('bad', mass=-1.0)])),
            ('spawn over the limit',
             self.sim.spawn([spec() for _ in range(MAX_PARTICLES)])),
            ('spawn a taken name', self.sim.spawn([spec('target')])),
            ('spawn in an unknown frame', self.sim.spawn([spec('n', frame_id='nowhere')])),
            ('impulse unknown id', self.sim.apply_impulse(123456789, '', '', vec(1, 0, 0))),
            ('impulse unknown name', self.sim.apply_impulse(0, 'ghost', '', vec(1, 0, 0))),
            ('impulse NaN', self.sim.apply_impulse(pid, '', '', vec(nan, 0, 0))),
            ('force bad mode', self.sim.apply_force(pid, '', '', vec(1, 0, 0), 9, 0.0)),
            ('force negative duration', self.sim.apply_force(
                pid, '', '', vec(1, 0, 0), ApplyForceRequest.DURATION, -1.0)),
            ('force Inf', self.sim.apply_force(
                pid, '', '', vec(inf, 0, 0), ApplyForceRequest.UNTIL_CLEARED, 0.0)),
            ('clear with nothing to clear', self.sim.apply_force(
                pid, '', '', vec(0, 0, 0), ApplyForceRequest.CLEAR, 0.0)),
            ('set_state NaN', self.sim.set_state(SetStateRequest(
                id=pid, set_position=True, position=vec(nan, 0, 0)))),
            ('set_state unknown id', self.sim.set_state(SetStateRequest(
                id=987654321, set_position=True))),
            ('remove unknown name', self.sim.remove([], ['target', 'ghost'])),
            ('remove unknown id', self.sim.remove([55555], [])),
            ('link unknown type', self.sim.add_link(AddLinkRequest(type='rope', a=pid,
                                                                   to_anchor=True))),
            ('link negative stiffness', self.sim.add_link(AddLinkRequest(
                type='spring', a=pid, to_anchor=True, stiffness=-1.0, rest_length=1.0))),
            ('link NaN', self.sim.add_link(AddLinkRequest(
                type='spring', a=pid, to_anchor=True, stiffness=nan))),
            ('link to unknown b', self.sim.add_link(AddLinkRequest(
                type='spring', a=pid, b_name='ghost', stiffness=1.0))),
            ('remove unknown link', self.sim.remove_link(999)),
            ('step 0', self.sim.step(0)),
            ('step over the limit', self.sim.step(10 ** 9)),
        ]
        for what, answer in refused:
            self.assertFalse(answer.success, what)
            self.assertTrue(answer.message, what + ': no message')
        after = self.sim.stats()
        self.assertEqual(after.state_hash, before.state_hash)
        self.assertEqual(after.particles, before.particles)
        self.assertEqual(after.force_generators, before.force_generators)
        self.assertEqual(after.sustained_forces, 0)
        self.assertEqual(after.commands_applied, before.commands_applied)


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'node_services', NodeServicesTest, sys.argv)
