"""Shared helpers for the rostest scripts: service proxies and fresh-message waits."""
import threading

import rospy
from std_srvs.srv import SetBool, Trigger

from mass_aggregate_sim.msg import (BodyArray, BodyShapeSpec, BodySpec, JointEndSpec,
                                    ParticleArray, ParticleSpec, SimStats)
from mass_aggregate_sim.srv import (AddBodySpring, AddForceField, AddJoint, AddLink,
                                    ApplyBodyImpulse, ApplyBodyWrench, ApplyForce, ApplyImpulse,
                                    GetBodyState, Overlap, Raycast,
                                    Remove, RemoveBody, RemoveForceField, RemoveJoint, RemoveLink,
                                    SetBodyState, SetHingeMotor, SetState, Spawn, SpawnBody, Step)

SERVICES = {
    'spawn': Spawn, 'remove': Remove, 'set_state': SetState, 'apply_force': ApplyForce,
    'apply_impulse': ApplyImpulse, 'add_link': AddLink, 'remove_link': RemoveLink,
    'pause': SetBool, 'step': Step, 'reset': Trigger,
}
BODY_SERVICES = {
    'spawn_body': SpawnBody, 'remove_body': RemoveBody, 'set_body_state': SetBodyState,
    'get_body_state': GetBodyState, 'apply_body_wrench': ApplyBodyWrench,
    'apply_body_impulse': ApplyBodyImpulse, 'add_joint': AddJoint, 'remove_joint': RemoveJoint,
    'set_hinge_motor': SetHingeMotor, 'raycast': Raycast, 'overlap': Overlap,
    'add_body_spring': AddBodySpring, 'add_force_field': AddForceField,
    'remove_force_field': RemoveForceField,
}


class SimClient:
    def __init__(self, ns='/mass_aggregate_sim'):
        self.ns = ns
        for name, srv in list(SERVICES.items()) + list(BODY_SERVICES.items()):
            rospy.wait_for_service(ns + '/' + name, timeout=20.0)
            setattr(self, name, rospy.ServiceProxy(ns + '/' + name, srv))
        self._cond = threading.Condition()
        self._latest = {}
        self._count = {'stats': 0, 'particles': 0, 'bodies': 0}
        rospy.Subscriber(ns + '/stats', SimStats, self._on, 'stats', queue_size=10)
        rospy.Subscriber(ns + '/particles', ParticleArray, self._on, 'particles', queue_size=10)
        rospy.Subscriber(ns + '/bodies', BodyArray, self._on, 'bodies', queue_size=10)

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


def shape(kind='box', half_extents=(0.5, 0.5, 0.5), radius=0.0, half_length=0.0,
          at=(0.0, 0.0, 0.0), q=(0.0, 0.0, 0.0, 1.0), density=0.0, friction=0.5, restitution=0.0):
    s = BodyShapeSpec()
    s.type = kind
    s.half_extents.x, s.half_extents.y, s.half_extents.z = half_extents
    s.radius, s.half_length, s.density, s.friction, s.restitution = radius, half_length, \
        density, friction, restitution
    s.pose.position.x, s.pose.position.y, s.pose.position.z = at
    s.pose.orientation.x, s.pose.orientation.y, s.pose.orientation.z, s.pose.orientation.w = q
    return s


def body(name='', x=(0.0, 0.0, 0.0), q=(0.0, 0.0, 0.0, 1.0), v=(0.0, 0.0, 0.0),
         w=(0.0, 0.0, 0.0), shapes=None, mass=1.0, kind=BodySpec.DYNAMIC, frame_id=''):
    """A body spec: by default a 1 kg unit cube."""
    b = BodySpec()
    b.name, b.frame_id, b.type, b.mass = name, frame_id, kind, mass
    b.pose.position.x, b.pose.position.y, b.pose.position.z = x
    b.pose.orientation.x, b.pose.orientation.y, b.pose.orientation.z, b.pose.orientation.w = q
    b.twist.linear.x, b.twist.linear.y, b.twist.linear.z = v
    b.twist.angular.x, b.twist.angular.y, b.twist.angular.z = w
    b.shapes = shapes if shapes is not None else [shape()]
    return b


def end(kind=JointEndSpec.WORLD, name='', id=0):
    e = JointEndSpec()
    e.kind, e.name, e.id = kind, name, id
    return e
