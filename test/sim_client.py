"""Shared helpers for the rostest scripts: service proxies and fresh-message waits."""
import threading

import rospy
from std_srvs.srv import SetBool, Trigger

from mass_aggregate_sim.msg import ParticleArray, ParticleSpec, SimStats
from mass_aggregate_sim.srv import (AddLink, ApplyForce, ApplyImpulse, Remove, RemoveLink,
                                    SetState, Spawn, Step)

SERVICES = {
    'spawn': Spawn, 'remove': Remove, 'set_state': SetState, 'apply_force': ApplyForce,
    'apply_impulse': ApplyImpulse, 'add_link': AddLink, 'remove_link': RemoveLink,
    'pause': SetBool, 'step': Step, 'reset': Trigger,
}


class SimClient:
    def __init__(self, ns='/mass_aggregate_sim'):
        self.ns = ns
        for name, srv in SERVICES.items():
            rospy.wait_for_service(ns + '/' + name, timeout=20.0)
            setattr(self, name, rospy.ServiceProxy(ns + '/' + name, srv))
        self._cond = threading.Condition()
        self._latest = {}
        self._count = {'stats': 0, 'particles': 0}
        rospy.Subscriber(ns + '/stats', SimStats, self._on, 'stats', queue_size=10)
        rospy.Subscriber(ns + '/particles', ParticleArray, self._on, 'particles', queue_size=10)

    def _on(self, msg, topic):
        with self._cond:
            self._latest[topic] = msg
            self._count[topic] += 1
            self._cond.notify_all()

    def fresh(self, topic, count=2, timeout=10.0):
        """The latest message after `count` new ones arrived: one published before the last
        request was applied may still be in flight, the second cannot be."""
        with self._cond:
            target = self._count[topic] + count
            if not self._cond.wait_for(lambda: self._count[topic] >= target, timeout):
                raise AssertionError('no %s message for %.0f s' % (topic, timeout))
            return self._latest[topic]

    def stats(self):
        return self.fresh('stats')

    def particle(self, particle_id):
        for p in self.fresh('particles').particles:
            if p.id == particle_id:
                return p
        return None

    def restart(self):
        """Paused and back at the loaded scene."""
        assert self.pause(True).success
        assert self.reset().success


def spec(name='', x=(0.0, 0.0, 0.0), v=(0.0, 0.0, 0.0), mass=1.0, radius=0.0, damping=0.0,
         frame_id='', fixed=False):
    s = ParticleSpec()
    s.name, s.frame_id, s.mass, s.radius, s.damping, s.fixed = name, frame_id, mass, radius, \
        damping, fixed
    s.position.x, s.position.y, s.position.z = x
    s.velocity.x, s.velocity.y, s.velocity.z = v
    return s
