#!/usr/bin/env python3
"""Soak (rostest: test/soak.test): `clients` threads flood the running node for `duration`
seconds with valid and invalid requests (spawn, remove, set_state, apply_force, apply_impulse,
add_link, remove_link, step while running, the body and joint services and queries, bad values)
and check that every valid request
answers success, every invalid one success=false with a message, none is lost (the node's
commands_applied equals the successes), ~stats keeps its rate, the node's RSS stays bounded,
and the node is alive at the end. Prints the figures."""
import math
import random
import sys
import threading
import time
import unittest
import xmlrpc.client

import rosgraph
import rosnode
import rospy
import rostest
from geometry_msgs.msg import Point, Vector3, Wrench

from mass_aggregate_sim.msg import JointEndSpec, SimStats
from mass_aggregate_sim.srv import (AddJointRequest, AddLinkRequest, ApplyBodyImpulseRequest,
                                    ApplyBodyWrenchRequest, ApplyForceRequest,
                                    GetBodyStateRequest, OverlapRequest, RaycastRequest,
                                    SetBodyStateRequest, SetStateRequest)
from sim_client import BODY_SERVICES, SERVICES, body, end, shape, spec

LIVE_PER_CLIENT = 12  # particles a client keeps alive at most (4 x 12 + 10 < max_particles)
LINKS_PER_CLIENT = 15  # links a client keeps at most (4 x 15 + 9 < max_links)
# Names a client reuses. Every name is a tf frame, and tf2 never forgets one (the node's own
# listener hears them: docs/RELIABILITY.md, known weakness): with unique names the RSS would grow
# with the number of names spawned, about 37 MiB in 60 s of this flood, not with any leak of the
# node's own. A pool of 64 per client keeps the frames at 256 while the names still change.
NAME_POOL = 64
BODIES_PER_CLIENT = 6  # bodies a client keeps alive at most (4 x 6 < max_bodies)
JOINTS_PER_CLIENT = 3


def vec(x, y, z):
    v = Vector3()
    v.x, v.y, v.z = x, y, z
    return v


def node_pid(node_name):
    """The node's pid through the ROS node API (getPid), not by searching process names."""
    uri = rosgraph.Master('/soak_test').lookupNode(node_name)
    code, _, pid = xmlrpc.client.ServerProxy(uri).getPid('/soak_test')
    assert code == 1, 'getPid failed'
    return pid


def rss_kib(pid):
    with open('/proc/%d/status' % pid) as status:
        for line in status:
            if line.startswith('VmRSS:'):
                return int(line.split()[1])
    raise AssertionError('no VmRSS for pid %d' % pid)


class Client(threading.Thread):
    """One client with its own persistent connections, a seeded random choice of requests, and
    its own particles (named c<index>_<n>, n < NAME_POOL, none taken twice at once) so its
    expectations never depend on other clients."""

    def __init__(self, index, ns, deadline):
        super().__init__(name='client%d' % index)
        self.index = index
        self.deadline = deadline
        self.random = random.Random(index)
        self.proxies = {name: rospy.ServiceProxy(ns + '/' + name, srv, persistent=True)
                        for name, srv in list(SERVICES.items()) + list(BODY_SERVICES.items())}
        self.bodies = []  # (id, name)
        self.joints = []
        self.body_serial = 0
        self.queries = 0  # successful requests that change nothing and are not recorded
        self.live = []  # (id, name)
        self.removed = []  # stale ids
        self.links = []
        self.serial = 0
        self.valid = 0
        self.invalid = 0
        self.successes = 0
        self.errors = []

    def call(self, service, expect_success, *args, recorded=True, **kwargs):
        try:
            answer = self.proxies[service](*args, **kwargs)
        except (rospy.ServiceException, OSError) as error:
            self.errors.append('%s: call lost: %s' % (service, error))
            return None
        if expect_success:
            self.valid += 1
        else:
            self.invalid += 1
        if answer.success:
            self.successes += 1
            if not recorded:
                self.queries += 1
        if answer.success != expect_success:
            self.errors.append('%s: expected success=%s, got %s: %s'
                               % (service, expect_success, answer.success, answer.message))
        elif not answer.message:
            self.errors.append('%s: answered without a message' % service)
        return answer

    def own(self):
        return self.random.choice(self.live)

    def spawn_valid(self):
        taken = set(name for _, name in self.live)
        while True:
            self.serial += 1
            name = 'c%d_%d' % (self.index, self.serial % NAME_POOL)
            if name not in taken:
                break
        x = (self.random.uniform(-3, 3), self.random.uniform(-3, 3), self.random.uniform(0.2, 4))
        answer = self.call('spawn', True, [spec(name, x, mass=self.random.uniform(0.1, 3.0),
                                                radius=0.05)])
        if answer is not None and answer.success:
            self.live.append((answer.ids[0], name))

    def spawn_body(self):
        taken = set(name for _, name in self.bodies)
        while True:
            self.body_serial += 1
            name = 'b%d_%d' % (self.index, self.body_serial % NAME_POOL)
            if name not in taken:
                break
        x = (self.random.uniform(-3, 3), self.random.uniform(-3, 3), self.random.uniform(0.5, 4))
        kind = self.random.choice([shape('box', (0.2, 0.15, 0.1)), shape('sphere', radius=0.15),
                                   shape('capsule', radius=0.1, half_length=0.2)])
        answer = self.call('spawn_body', True, [body(name, x, shapes=[kind],
                                                     mass=self.random.uniform(0.5, 5.0))])
        if answer is not None and answer.success:
            self.bodies.append((answer.ids[0], name))

    def body_step_once(self):
        """The body and joint services, valid and invalid."""
        r = self.random.random()
        nan = float('nan')
        if not self.bodies or (r < 0.15 and len(self.bodies) < BODIES_PER_CLIENT):
            self.spawn_body()
        elif r < 0.22:
            bid, _ = self.bodies.pop(self.random.randrange(len(self.bodies)))
            self.joints = [j for j in self.joints if j[1] != bid]
            self.call('remove_body', True, [bid], [])
        elif r < 0.30:
            _, name = self.random.choice(self.bodies)
            self.call('apply_body_wrench', True, ApplyBodyWrenchRequest(
                name=name, reference_frame=name, wrench=Wrench(vec(0.0, 0.0, 30.0),
                                                               vec(0.0, 0.0, 0.5)),
                mode=ApplyBodyWrenchRequest.ONE_STEP))
        elif r < 0.38:
            bid, _ = self.random.choice(self.bodies)
            self.call('apply_body_impulse', True, ApplyBodyImpulseRequest(
                id=bid, impulse=vec(0.0, 0.5, 1.0), angular_impulse=vec(0.01, 0.0, 0.0)))
        elif r < 0.44:
            _, name = self.random.choice(self.bodies)
            self.call('set_body_state', True, SetBodyStateRequest(
                name=name, set_twist=True, twist=body(v=(0.0, 0.0, 1.0)).twist))
        elif r < 0.50:
            _, name = self.random.choice(self.bodies)
            self.call('get_body_state', True, GetBodyStateRequest(name=name), recorded=False)
        elif r < 0.56 and len(self.joints) < JOINTS_PER_CLIENT:
            bid, _ = self.random.choice(self.bodies)
            answer = self.call('add_joint', True, AddJointRequest(
                type='distance', a=end(JointEndSpec.BODY, id=bid), b=end(),
                anchor=Point(0.0, 0.0, 5.0), min_length=0.0, max_length=6.0))
            if answer is not None and answer.success:
                self.joints.append((answer.joint_id, bid))
        elif r < 0.62 and self.joints:
            joint_id, _ = self.joints.pop()
            self.call('remove_joint', True, joint_id)
        elif r < 0.66:
            self.call('raycast', True, RaycastRequest(origin=Point(0.0, 0.0, 10.0),
                                                      direction=vec(0.0, 0.0, -1.0),
                                                      max_distance=20.0), recorded=False)
        elif r < 0.70:
            self.call('overlap', True, OverlapRequest(shape=OverlapRequest.SPHERE, radius=1.0,
                                                      pose=body().pose), recorded=False)
        # Invalid body requests.
        elif r < 0.76:
            self.call('spawn_body', False, [body('bad_body', (nan, 0.0, 1.0))])
        elif r < 0.82:
            self.call('spawn_body', False, [body('bad_q', q=(0.0, 0.0, 0.0, 0.0))])
        elif r < 0.86:
            self.call('spawn_body', False, [body('bad_size', shapes=[shape('sphere',
                                                                            radius=-1.0)])])
        elif r < 0.90:
            bid, _ = self.random.choice(self.bodies)
            self.call('add_joint', False, AddJointRequest(
                type='hinge', a=end(JointEndSpec.BODY, id=bid), b=end(JointEndSpec.BODY, id=bid),
                axis=vec(0.0, 1.0, 0.0)))
        elif r < 0.94:
            _, name = self.random.choice(self.bodies)
            self.call('apply_body_wrench', False, ApplyBodyWrenchRequest(
                name=name, wrench=Wrench(vec(math.inf, 0.0, 0.0), vec(0.0, 0.0, 0.0))))
        else:
            self.call('get_body_state', False, GetBodyStateRequest(name='nobody'),
                      recorded=False)

    def step_once(self):
        if self.random.random() < 0.35:
            self.body_step_once()
            return
        r = self.random.random()
        nan = float('nan')
        if len(self.live) < 2 or (r < 0.15 and len(self.live) < LIVE_PER_CLIENT):
            self.spawn_valid()
        elif r < 0.25:
            pid, _ = self.live.pop(self.random.randrange(len(self.live)))
            self.links = [link for link in self.links if pid not in link[1:]]
            if self.call('remove', True, [pid], []) is not None:
                self.removed.append(pid)
        elif r < 0.33:
            pid, _ = self.own()
            self.call('apply_impulse', True, pid, '', '', vec(0.1, 0.0, 0.5))
        elif r < 0.41:
            _, name = self.own()
            self.call('set_state', True, SetStateRequest(name=name, set_velocity=True,
                                                        velocity=vec(0.0, 0.2, 0.0)))
        elif r < 0.49:
            pid, _ = self.own()
            self.call('apply_force', True, pid, '', '', vec(0.0, 0.0, 2.0),
                      ApplyForceRequest.ONE_STEP, 0.0)
        elif r < 0.55 and len(self.links) < LINKS_PER_CLIENT:
            (a, _), (b, _) = self.random.sample(self.live, 2)
            answer = self.call('add_link', True, AddLinkRequest(type='spring', a=a, b=b,
                                                                 stiffness=5.0, rest_length=-1.0))
            if answer is not None and answer.success:
                self.links.append((answer.link_id, a, b))
        elif r < 0.60 and self.links or len(self.links) >= LINKS_PER_CLIENT:
            link_id, _, _ = self.links.pop()
            self.call('remove_link', True, link_id)
        # Invalid requests, each refused for a different rule.
        elif r < 0.64:
            self.call('spawn', False, [spec('bad', (0.0, nan, 1.0))])
        elif r < 0.68:
            self.call('spawn', False, [spec('heavy_bad', mass=-1.0)])
        elif r < 0.72:
            self.call('spawn', False, [spec('far_bad', (2e6, 0.0, 0.0))])
        elif r < 0.75:
            _, name = self.own()
            self.call('spawn', False, [spec(name)])  # a taken name
        elif r < 0.79 and self.removed:
            self.call('apply_impulse', False, self.random.choice(self.removed), '', '',
                      vec(1.0, 0.0, 0.0))  # a stale id
        elif r < 0.83:
            pid, _ = self.own()
            self.call('apply_impulse', False, pid, '', '', vec(math.inf, 0.0, 0.0))
        elif r < 0.87:
            self.call('set_state', False, SetStateRequest(name='nobody', set_position=True))
        elif r < 0.91:
            pid, _ = self.own()
            self.call('add_link', False, AddLinkRequest(type='spring', a=pid, to_anchor=True,
                                                        stiffness=-1.0))
        elif r < 0.94:
            self.call('step', False, 5)  # the node is running: refused
        elif r < 0.97:
            pid, _ = self.own()
            self.call('apply_force', False, pid, '', '', vec(1.0, 0.0, 0.0), 9, 0.0)
        else:
            self.call('remove', False, [], ['nobody'])

    def run(self):
        try:
            while time.time() < self.deadline:
                self.step_once()
        finally:
            for proxy in self.proxies.values():
                proxy.close()


class SoakTest(unittest.TestCase):
    def test_flood(self):
        rospy.init_node('soak_test')
        ns = rospy.get_param('~node', '/soak_sim')
        duration = float(rospy.get_param('~duration', 60.0))
        clients = int(rospy.get_param('~clients', 4))
        publish_rate = float(rospy.get_param('~publish_rate', 20.0))
        for name in list(SERVICES) + list(BODY_SERVICES):
            rospy.wait_for_service(ns + '/' + name, timeout=30.0)
        pid = node_pid(ns)

        stats = {'count': 0, 'last': None}
        lock = threading.Lock()

        rtf = []

        def on_stats(msg):
            with lock:
                stats['count'] += 1
                stats['last'] = msg
                if not msg.paused:
                    rtf.append(msg.real_time_factor)

        rospy.Subscriber(ns + '/stats', SimStats, on_stats, queue_size=50)
        time.sleep(2.0)
        with lock:
            start_count = stats['count']
            start_commands = stats['last'].commands_applied
            del rtf[:]
        start = time.time()
        rss_start = rss_kib(pid)
        samples = [rss_start]
        workers = [Client(i, ns, start + duration) for i in range(clients)]
        for worker in workers:
            worker.start()
        while any(worker.is_alive() for worker in workers):
            time.sleep(1.0)
            samples.append(rss_kib(pid))
        for worker in workers:
            worker.join()
        elapsed = time.time() - start
        time.sleep(0.5)
        with lock:
            stats_count = stats['count'] - start_count
        stats_rate = stats_count / (elapsed + 0.5)

        # The node is alive and answers; then its stats count every accepted request.
        alive = rospy.ServiceProxy(ns + '/pause', SERVICES['pause'])(True)
        self.assertTrue(alive.success, alive.message)
        deadline = time.time() + 5.0
        while time.time() < deadline:
            with lock:
                last = stats['last']
            if last.paused:
                break
            time.sleep(0.1)
        valid = sum(w.valid for w in workers)
        invalid = sum(w.invalid for w in workers)
        successes = sum(w.successes for w in workers)
        queries = sum(w.queries for w in workers)
        errors = [e for w in workers for e in w.errors]
        peak = max(samples)
        rss_first_third = max(samples[:max(1, len(samples) // 3)])
        print('[ soak ] %d clients, %.1f s: %d requests handled (%d valid, %d invalid), %.0f/s; '
              '~stats %.1f Hz (expected %.0f); RSS start %d KiB, peak %d KiB, first third peak '
              '%d KiB; real-time factor mean %.3f, min %.3f, overruns %d; %d errors'
              % (clients, elapsed, valid + invalid, valid, invalid, (valid + invalid) / elapsed,
                 stats_rate, publish_rate, rss_start, peak, rss_first_third,
                 sum(rtf) / max(1, len(rtf)), min(rtf or [0.0]), last.overruns, len(errors)))
        sys.stdout.flush()
        self.assertEqual(errors, [], '\n'.join(errors[:20]))
        self.assertGreater(valid, 1000)
        self.assertGreater(invalid, 300)
        # No request lost: one command applied per success (queries are not recorded), plus the
        # final pause.
        self.assertEqual(last.commands_applied - start_commands, successes - queries + 1)
        self.assertGreaterEqual(stats_rate, 0.8 * publish_rate)
        # Bounded memory: after the first third (buffers grown to their working size) the RSS
        # grows by less than 16 MiB, and it never exceeds 4 times the starting RSS.
        self.assertLess(peak - rss_first_third, 16 * 1024)
        self.assertLess(peak, 4 * rss_start)
        self.assertTrue(rosnode.rosnode_ping(ns, max_count=1))


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'soak', SoakTest, sys.argv)
