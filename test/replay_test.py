#!/usr/bin/env python3
"""Records a driven node's ~commands (and nothing else) with rosbag, replays the bag into a second
node with scripts/replay_commands.py, and expects the same final state hash; a third node with
another integrator must be named as different (rostest: test/replay.test). The drive includes live
reconfigures of the integrator, gravity and the body solver's passes, a ~step action that is
cancelled, and bodies: spawns (one in a tf frame), joints (a hinge with a motor changed at
runtime, a distance joint to a particle), a bungee from a body to a particle given in a tf frame,
wrenches (one for a duration), impulses, teleports and removals."""
import math
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import actionlib
import rosbag
import rospkg
import rospy
import rostest
import tf2_ros
from dynamic_reconfigure.client import Client
from geometry_msgs.msg import Point, TransformStamped, Vector3, Wrench

from mass_aggregate_sim.msg import JointEndSpec, StepAction, StepGoal
from mass_aggregate_sim.srv import (AddBodySpringRequest, AddForceFieldRequest, AddJointRequest,
                                    AddLinkRequest,
                                    ApplyBodyImpulseRequest,
                                    ApplyBodyWrenchRequest, ApplyForceRequest,
                                    SetBodyStateRequest, SetHingeMotorRequest, SetStateRequest)
from sim_client import SimClient, body, end, shape, spec

TARGET_LIMIT = 2000  # /replay_target's ~max_steps_per_request (test/replay.test)


def vec(x, y, z):
    v = Vector3()
    v.x, v.y, v.z = x, y, z
    return v


class ReplayTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('replay_test')
        cls.sim = SimClient('/mass_aggregate_sim')
        SimClient('/replay_target')  # waits for its services
        SimClient('/differing_target')
        cls.action = actionlib.SimpleActionClient('/mass_aggregate_sim/step', StepAction)
        assert cls.action.wait_for_server(rospy.Duration(30.0))
        cls.reconfigure = Client('/mass_aggregate_sim', timeout=30.0)
        cls.dir = tempfile.mkdtemp(prefix='mas_replay_')
        cls.script = os.path.join(rospkg.RosPack().get_path('mass_aggregate_sim'), 'scripts',
                                  'replay_commands.py')
        # A frame for a spawn given in another frame (recorded already in ~frame_id).
        cls.tf = tf2_ros.StaticTransformBroadcaster()
        t = TransformStamped()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id = 'world'
        t.child_frame_id = 'replay_frame'
        t.transform.translation = vec(-1.0, 0.5, 3.0)
        t.transform.rotation.x = math.sqrt(0.5)
        t.transform.rotation.w = math.sqrt(0.5)
        cls.tf.sendTransform(t)
        buffer = tf2_ros.Buffer()
        listener = tf2_ros.TransformListener(buffer)
        buffer.lookup_transform('world', 'replay_frame', rospy.Time(0), rospy.Duration(10.0))
        del listener

    def record(self, bag):
        recorder = subprocess.Popen(
            ['rosbag', 'record', '-O', bag, '/mass_aggregate_sim/commands',
             '__name:=replay_test_record'],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        # Wait until the recorder has subscribed to the commands topic.
        deadline = time.time() + 20.0
        while time.time() < deadline:
            subscriptions = rospy.get_master().getSystemState()[2][1]
            subscribers = [nodes for topic, nodes in subscriptions
                           if topic == '/mass_aggregate_sim/commands']
            if subscribers and any('replay_test_record' in n for n in subscribers[0]):
                break
            time.sleep(0.2)
        time.sleep(0.5)
        return recorder

    def stop(self, recorder, bag):
        recorder.send_signal(signal.SIGINT)
        recorder.wait(timeout=20.0)
        deadline = time.time() + 10.0
        while not os.path.exists(bag) and time.time() < deadline:
            time.sleep(0.1)
        self.assertTrue(os.path.exists(bag), 'rosbag wrote no ' + bag)

    def drive(self):
        """Requests while running (applied at whatever step they land on) and while paused."""
        sim = self.sim
        self.assertTrue(sim.pause(False).success)
        time.sleep(0.3)
        spawned = sim.spawn([spec('ball', (0.5, 0.0, 4.0), (1.0, 0.0, 0.0), mass=0.7),
                             spec('', (2.0, 0.0, 4.0), mass=1.3)])
        self.assertTrue(spawned.success, spawned.message)
        time.sleep(0.2)
        self.assertTrue(sim.apply_impulse(0, 'spring_9', '', vec(0.0, 1.0, 2.0)).success)
        self.assertTrue(sim.apply_force(spawned.ids[1], '', '', vec(0.0, 0.0, 30.0),
                                        ApplyForceRequest.DURATION, 0.2).success)
        link = sim.add_link(AddLinkRequest(type='spring', a_name='ball', b=spawned.ids[1],
                                           stiffness=40.0, rest_length=-1.0))
        self.assertTrue(link.success, link.message)
        # Bodies while running: a box on a hinge with a motor, a capsule on a rod to a particle.
        bodies = sim.spawn_body([
            body('crate', x=(1.0, 2.0, 4.0), q=(0.0, 0.0, 0.2588190451025208, 0.9659258262890683),
                 v=(0.5, 0.0, 0.0), shapes=[shape('box', (0.3, 0.2, 0.1))]),
            body('', x=(0.0, 0.0, 0.0), frame_id='replay_frame',
                 shapes=[shape('capsule', radius=0.1, half_length=0.3),
                         shape('sphere', radius=0.15, at=(0.0, 0.0, 0.4))], mass=2.0)])
        self.assertTrue(bodies.success, bodies.message)
        hinge = sim.add_joint(AddJointRequest(
            type='hinge', name='axle', a=end(JointEndSpec.BODY, 'crate'), b=end(),
            anchor=Point(1.0, 2.0, 4.5), axis=Vector3(0.0, 1.0, 0.0), motor=True,
            motor_speed=1.5, max_motor_torque=20.0, min_length=-1.0, max_length=-1.0))
        self.assertTrue(hinge.success, hinge.message)
        rod = sim.add_joint(AddJointRequest(
            type='distance', a=end(JointEndSpec.BODY, id=bodies.ids[1]),
            b=end(JointEndSpec.PARTICLE, 'spring_3'), anchor=Point(-1.0, 0.5, 3.0),
            min_length=-1.0, max_length=-1.0))
        self.assertTrue(rod.success, rod.message)
        # A bungee from the crate to a particle, given in the turned frame.
        bungee = sim.add_body_spring(AddBodySpringRequest(
            type='bungee', a=end(JointEndSpec.BODY, 'crate'),
            b=end(JointEndSpec.PARTICLE, 'spring_5'), frame_id='replay_frame',
            anchor=Point(0.2, 0.1, 0.0), stiffness=25.0, damping=0.5, rest_length=0.5))
        self.assertTrue(bungee.success, bungee.message)
        # Water around the crate, its surface given in the turned frame, with drag on a particle
        # and the capsule; the capsule's drag removed again.
        water = sim.add_force_field(AddForceFieldRequest(
            type='buoyancy', body_names=['crate'], liquid_density=800.0, surface_height=3.9,
            up=Vector3(0.1, 0.0, 1.0), frame_id='replay_frame'))
        self.assertTrue(water.success, water.message)
        drag = sim.add_force_field(AddForceFieldRequest(
            type='drag', particle_names=['spring_2'], body_ids=[bodies.ids[1]], k1=0.3, k2=0.05,
            angular=0.02))
        self.assertTrue(drag.success, drag.message)
        self.assertTrue(sim.remove_force_field(force_id=drag.force_ids[1]).success)
        self.assertTrue(sim.apply_body_wrench(ApplyBodyWrenchRequest(
            name='crate', reference_point=Point(1.2, 2.0, 4.0), wrench=Wrench(
                Vector3(0.0, 0.0, 40.0), Vector3(0.0, 0.0, 1.0)),
            mode=ApplyBodyWrenchRequest.DURATION, duration=0.35)).success)
        time.sleep(0.3)
        self.assertTrue(sim.pause(True).success)
        self.assertTrue(sim.step(17).success)
        self.assertTrue(sim.set_state(SetStateRequest(name='ball', set_velocity=True,
                                                      velocity=vec(0.0, 0.0, 3.0))).success)
        self.assertTrue(sim.apply_body_impulse(ApplyBodyImpulseRequest(
            id=bodies.ids[1], reference_frame='crate', reference_point=Point(0.1, 0.0, 0.0),
            impulse=vec(0.0, 2.0, 0.0), angular_impulse=vec(0.1, 0.0, 0.0))).success)
        self.assertTrue(sim.set_hinge_motor(SetHingeMotorRequest(
            name='axle', enabled=True, speed=-2.0, max_torque=10.0)).success)
        self.assertTrue(sim.step(5).success)
        # Live settings, recorded on ~commands and replayed through ~set_parameters.
        config = self.reconfigure.update_configuration({'integrator': 'rk4', 'gravity_z': -4.5,
                                                        'body_iterations': 3,
                                                        'body_relax_iterations': 1})
        self.assertEqual(config['integrator'], 'rk4')
        self.assertEqual(config['body_iterations'], 3)
        self.assertTrue(sim.step(9).success)
        # A long ~step action, cancelled once it has reported progress: it stops at a step
        # boundary, and the steps it took are recorded.
        feedback = []
        self.action.send_goal(StepGoal(steps=5000000), feedback_cb=feedback.append)
        # Longer than the replay target's limit on one goal: the replay has to split the gap.
        deadline = time.time() + 30.0
        while (not feedback or feedback[-1].steps_done < 3 * TARGET_LIMIT) and \
                time.time() < deadline:
            time.sleep(0.02)
        self.assertTrue(feedback, 'no feedback from the ~step action')
        self.assertTrue(sim.apply_impulse(0, 'spring_5', '', vec(0.5, 0.0, 0.0)).success)
        self.action.cancel_goal()
        self.assertTrue(self.action.wait_for_result(rospy.Duration(30.0)))
        self.assertEqual(self.action.get_state(), actionlib.GoalStatus.PREEMPTED)
        result = self.action.get_result()
        self.assertGreater(result.steps_done, 0)
        self.assertLess(result.steps_done, 5000000)
        config = self.reconfigure.update_configuration({'integrator': 'semi_implicit_euler',
                                                        'substeps': 2})
        self.assertEqual(config['substeps'], 2)
        self.assertTrue(sim.remove([], ['bungee_9']).success)
        self.assertTrue(sim.set_body_state(SetBodyStateRequest(
            name='crate', set_pose=True, pose=body(x=(1.0, 2.0, 5.0)).pose, set_twist=True,
            twist=body(w=(0.0, 1.0, 0.0)).twist)).success)
        self.assertTrue(sim.remove_joint(rod.joint_id).success)
        self.assertTrue(sim.pause(False).success)
        time.sleep(0.3)
        self.assertTrue(sim.apply_force(0, 'ball', '', vec(5.0, 0.0, 0.0),
                                        ApplyForceRequest.ONE_STEP, 0.0).success)
        self.assertTrue(sim.remove_link(link.link_id).success)
        self.assertTrue(sim.remove_body([bodies.ids[1]], []).success)
        time.sleep(0.2)
        self.assertTrue(sim.pause(True).success)
        # Let a few stats messages (with every command counted) reach the bag.
        final = sim.stats()
        sim.stats()
        return final

    def replay(self, bag, target='/replay_target'):
        env = dict(os.environ)
        env['PATH'] = '/usr/bin:' + env.get('PATH', '')
        return subprocess.run(['/usr/bin/python3', self.script, bag, '--target', target],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=90, env=env)

    def test_recorded_bag_replays_to_the_same_hash(self):
        bag = os.path.join(self.dir, 'drive.bag')
        recorder = self.record(bag)
        final = self.drive()
        self.stop(recorder, bag)
        self.assertGreater(final.commands_applied, 10)
        with rosbag.Bag(bag) as recorded:
            steps = sorted(m.step for _, m, _ in recorded.read_messages(
                topics=['/mass_aggregate_sim/commands']))
        longest = max(b - a for a, b in zip(steps, steps[1:]))
        self.assertGreater(longest, 2 * TARGET_LIMIT)
        result = self.replay(bag)
        self.assertEqual(result.returncode, 0, result.stdout)
        # The longest gap went as several goals, each within the target's limit.
        found = re.search(r'\((\d+) ~step goals of at most (\d+) steps\)', result.stdout)
        self.assertIsNotNone(found, result.stdout)
        self.assertEqual(int(found.group(2)), TARGET_LIMIT)
        self.assertGreater(int(found.group(1)), longest // TARGET_LIMIT)
        # The replayed node's own final hash, not only the recorded one, must be the driven
        # node's final hash, at the same step.
        found = re.search(r'to step (\d+): state hash (\d+), recorded (\d+): match', result.stdout)
        self.assertIsNotNone(found, result.stdout)
        self.assertEqual(int(found.group(1)), final.step)
        self.assertEqual(int(found.group(2)), final.state_hash)
        self.assertEqual(int(found.group(3)), final.state_hash)
        self.assertGreater(final.step, 0)
        # A node started with another integrator: the replay names the difference.
        result = self.replay(bag, '/differing_target')
        self.assertNotEqual(result.returncode, 0, result.stdout)
        self.assertIn('integrator: target rk4, recorded velocity_verlet', result.stdout)


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'replay', ReplayTest, sys.argv)
