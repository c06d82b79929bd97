#!/usr/bin/env python3
"""Replays the commands recorded in a bag into a running mass_aggregate_sim node and checks that
the final state hash equals the recorded one.

The bag must hold the recording node's ~commands (from its first command on) and ~stats. The
target node must have loaded the same scene with the same parameters (checked through the scene
hash). The target is paused and reset, then every recorded command is re-issued at the step it
was applied at: the script steps the target to that step first (~step), so wall-clock timing
plays no part. Pause and step commands are not re-issued: the steps come from the stamps.

Usage: replay_commands.py BAG [--source /mass_aggregate_sim] [--target /mass_aggregate_sim]
Exit status 0 when the hashes match, 1 when they differ or the replay fails.
"""
import argparse
import sys

import rosbag
import rospy
from std_srvs.srv import SetBool, Trigger, TriggerRequest

from mass_aggregate_sim.msg import SimStats
from mass_aggregate_sim.srv import (AddLink, ApplyForce, ApplyImpulse, Remove, RemoveLink,
                                    SetState, Spawn, Step)

SERVICES = {
    'spawn': Spawn,
    'remove': Remove,
    'set_state': SetState,
    'apply_force': ApplyForce,
    'apply_impulse': ApplyImpulse,
    'add_link': AddLink,
    'remove_link': RemoveLink,
}


def read_bag(path, source):
    commands, stats = [], []
    with rosbag.Bag(path) as bag:
        for topic, msg, _ in bag.read_messages(topics=[source + '/commands', source + '/stats']):
            (commands if topic.endswith('/commands') else stats).append(msg)
    return sorted(commands, key=lambda c: c.sequence), stats


class Target:
    def __init__(self, ns):
        self.ns = ns
        for name in list(SERVICES) + ['pause', 'step', 'reset']:
            rospy.wait_for_service(ns + '/' + name, timeout=10.0)
        self.proxies = {name: rospy.ServiceProxy(ns + '/' + name, srv)
                        for name, srv in SERVICES.items()}
        self.pause = rospy.ServiceProxy(ns + '/pause', SetBool)
        self.step_srv = rospy.ServiceProxy(ns + '/step', Step)
        self.reset_srv = rospy.ServiceProxy(ns + '/reset', Trigger)
        self.step = 0
        self.hash = None

    def stats(self):
        return rospy.wait_for_message(self.ns + '/stats', SimStats, timeout=10.0)

    def reset(self):
        answer = self.reset_srv(TriggerRequest())
        if not answer.success:
            raise RuntimeError('reset refused: ' + answer.message)
        self.step = 0
        self.hash = None

    def step_to(self, step):
        if step < self.step:
            raise RuntimeError('command stamped step %d, but the target is at %d' % (step, self.step))
        if step == self.step:
            return
        answer = self.step_srv(step - self.step)
        if not answer.success:
            raise RuntimeError('step refused: ' + answer.message)
        self.step = answer.step
        self.hash = answer.state_hash

    def call(self, service, raw):
        srv = SERVICES[service]
        request = srv._request_class()
        request.deserialize(bytes(raw))
        answer = self.proxies[service](request)
        if not answer.success:
            raise RuntimeError('%s refused on replay: %s' % (service, answer.message))
        self.hash = None


def replay(bag_path, source, target_ns):
    commands, stats = read_bag(bag_path, source)
    if not stats:
        raise RuntimeError('the bag has no %s/stats message' % source)
    final = stats[-1]
    to_replay = [c for c in commands if c.sequence < final.commands_applied]
    if final.commands_applied and (not to_replay or to_replay[0].sequence != 0):
        raise RuntimeError('the bag starts after the node\'s first command: record from the start')
    for expected, command in enumerate(to_replay):
        if command.sequence != expected:
            raise RuntimeError('command %d is missing from the bag' % expected)
    if len(to_replay) != final.commands_applied:
        raise RuntimeError('the bag holds %d of the %d commands' % (len(to_replay),
                                                                   final.commands_applied))

    target = Target(target_ns)
    if not target.pause(True).success:
        raise RuntimeError('the target refused to pause')
    target.reset()
    scene_hash = target.stats().scene_hash
    if scene_hash != final.scene_hash:
        raise RuntimeError('the target loaded another scene (hash %d, recorded %d)'
                           % (scene_hash, final.scene_hash))
    for command in to_replay:
        if command.service in ('pause', 'step'):
            continue
        target.step_to(command.step)
        if command.service == 'reset':
            target.reset()
        else:
            target.call(command.service, command.request)
    target.step_to(final.step)
    if target.hash is None:
        while True:
            stats = target.stats()
            if stats.paused and stats.step == final.step:
                target.hash = stats.state_hash
                break
    return len(to_replay), final, target.hash


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('bag')
    parser.add_argument('--source', default='/mass_aggregate_sim',
                        help='namespace of the recorded node')
    parser.add_argument('--target', default='/mass_aggregate_sim',
                        help='namespace of the node to replay into')
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node('replay_commands', anonymous=True)
    try:
        count, final, replayed = replay(args.bag, args.source.rstrip('/'), args.target.rstrip('/'))
    except (RuntimeError, rospy.ROSException, rospy.ServiceException) as error:
        print('replay failed: %s' % error)
        return 1
    match = replayed == final.state_hash
    print('replayed %d commands to step %d: state hash %d, recorded %d: %s'
          % (count, final.step, replayed, final.state_hash, 'match' if match else 'MISMATCH'))
    return 0 if match else 1


if __name__ == '__main__':
    sys.exit(main())
