#!/usr/bin/env python3
"""Replays the commands recorded in a bag into a running mass_aggregate_sim node and checks, at
every command, that the target's state hash equals the recorded one.

The bag needs the recording node's ~commands only, from its first command on: each command
carries the step it was applied at, the state hash and the configuration at that boundary, and the
scene hash. The target is paused and reset, its configuration and scene are compared with the
recording's (a difference is named, e.g. "integrator: target rk4, recorded semi_implicit_euler"),
then every command is re-issued at its step: the script steps the paused target there with the
~step action, so wall-clock timing plays no part (a gap longer than the target's
~max_steps_per_request goes as several goals, each within that limit). A recorded reconfigure is
sent to the target's
~set_parameters; pause and step commands are checkpoints (their steps come from the stamps). The
first command whose state differs is named, with the configuration lines that differ.

Usage: replay_commands.py BAG [--source /mass_aggregate_sim] [--target /mass_aggregate_sim]
Exit status 0 when every hash matches, 1 when one differs or the replay fails.
"""
import argparse
import sys
import threading

import actionlib
import rosbag
import rospy
from dynamic_reconfigure.msg import Config
from dynamic_reconfigure.srv import Reconfigure
from std_srvs.srv import SetBool, Trigger, TriggerRequest

from mass_aggregate_sim.msg import Command, StepAction, StepGoal
from mass_aggregate_sim.srv import (AddBodySpring, AddForceField, AddJoint, AddLink,
                                    ApplyBodyImpulse, ApplyBodyWrench,
                                    ApplyForce, ApplyImpulse, Remove, RemoveBody,
                                    RemoveForceField, RemoveJoint, RemoveLink, SetBodyState,
                                    SetHingeMotor, SetState, Spawn, SpawnBody)

SERVICES = {
    'spawn': Spawn,
    'remove': Remove,
    'set_state': SetState,
    'apply_force': ApplyForce,
    'apply_impulse': ApplyImpulse,
    'add_link': AddLink,
    'remove_link': RemoveLink,
    'spawn_body': SpawnBody,
    'remove_body': RemoveBody,
    'set_body_state': SetBodyState,
    'apply_body_wrench': ApplyBodyWrench,
    'apply_body_impulse': ApplyBodyImpulse,
    'add_joint': AddJoint,
    'remove_joint': RemoveJoint,
    'set_hinge_motor': SetHingeMotor,
    'add_body_spring': AddBodySpring,
    'add_force_field': AddForceField,
    'remove_force_field': RemoveForceField,
}
CHECKPOINTS = ('pause', 'step')
WAIT = 60.0  # s of wall time for any one answer
# The node's ~max_steps_per_request when the parameter is not set: the largest goal it accepts.
DEFAULT_MAX_STEPS = 100000


class ReplayError(RuntimeError):
    pass


def read_bag(path, source):
    commands = []
    with rosbag.Bag(path) as bag:
        for _, msg, _ in bag.read_messages(topics=[source + '/commands']):
            commands.append(msg)
    return sorted(commands, key=lambda c: c.sequence)


def parse_configuration(text):
    lines = {}
    for line in text.splitlines():
        key, _, value = line.partition(':')
        if key:
            lines[key.strip()] = value.strip()
    return lines


def configuration_difference(target, recorded):
    """The lines that differ, as 'key: target X, recorded Y'; empty when equal."""
    mine, theirs = parse_configuration(target), parse_configuration(recorded)
    return ['%s: target %s, recorded %s' % (key, mine.get(key, '(none)'), theirs.get(key, '(none)'))
            for key in sorted(set(mine) | set(theirs)) if mine.get(key) != theirs.get(key)]


def describe(command):
    return 'command %d (%s at step %d)' % (command.sequence, command.service, command.step)


class Target:
    """The node replayed into: its services, its ~step action, and its own ~commands, whose
    records of the replayed requests carry the target's state hash at each boundary."""

    def __init__(self, ns):
        self.ns = ns
        for name in list(SERVICES) + ['pause', 'reset', 'set_parameters']:
            rospy.wait_for_service(ns + '/' + name, timeout=WAIT)
        self.proxies = {name: rospy.ServiceProxy(ns + '/' + name, srv)
                        for name, srv in SERVICES.items()}
        self.pause = rospy.ServiceProxy(ns + '/pause', SetBool)
        self.reset_srv = rospy.ServiceProxy(ns + '/reset', Trigger)
        self.reconfigure = rospy.ServiceProxy(ns + '/set_parameters', Reconfigure)
        self.action = actionlib.SimpleActionClient(ns + '/step', StepAction)
        if not self.action.wait_for_server(rospy.Duration(WAIT)):
            raise ReplayError('the target has no %s/step action' % ns)
        self.cond = threading.Condition()
        self.echoes = []
        self.subscriber = rospy.Subscriber(ns + '/commands', Command, self._on_command,
                                           queue_size=1000)
        deadline = rospy.get_time() + WAIT
        while self.subscriber.get_num_connections() == 0:
            if rospy.get_time() > deadline:
                raise ReplayError('could not subscribe to %s/commands' % ns)
            rospy.sleep(0.05)
        self.step = 0
        # The target refuses a ~step goal of more steps than this: longer gaps are split.
        self.max_steps = int(rospy.get_param(ns + '/max_steps_per_request', DEFAULT_MAX_STEPS))
        if self.max_steps < 1:
            raise ReplayError('%s/max_steps_per_request is %d' % (ns, self.max_steps))
        self.goals = 0

    def _on_command(self, msg):
        with self.cond:
            self.echoes.append(msg)
            self.cond.notify_all()

    def echo(self, service):
        """The target's record of the request just made (the next one of that service)."""
        with self.cond:
            found = self.cond.wait_for(
                lambda: any(e.service == service for e in self.echoes), WAIT)
            if not found:
                raise ReplayError('the target recorded no %s command' % service)
            while True:
                echo = self.echoes.pop(0)
                if echo.service == service:
                    return echo

    def forget_echoes(self):
        with self.cond:
            del self.echoes[:]

    def checkpoint(self):
        """The target's record of a ~pause(true): its state hash and configuration now."""
        self.forget_echoes()
        if not self.pause(True).success:
            raise ReplayError('the target refused to pause')
        return self.echo('pause')

    def reset(self):
        self.forget_echoes()
        answer = self.reset_srv(TriggerRequest())
        if not answer.success:
            raise ReplayError('reset refused: ' + answer.message)
        self.step = 0
        return self.echo('reset')

    def step_to(self, step):
        if step < self.step:
            raise ReplayError('a command stamped step %d, but the target is at %d'
                              % (step, self.step))
        while self.step < step:
            steps = min(step - self.step, self.max_steps)
            self.action.send_goal(StepGoal(steps=steps))
            self.goals += 1
            if not self.action.wait_for_result(rospy.Duration(3600.0)):
                raise ReplayError('no result from the ~step action')
            result = self.action.get_result()
            if self.action.get_state() != actionlib.GoalStatus.SUCCEEDED:
                raise ReplayError('step refused: ' + (result.message if result else 'no result'))
            if result.step != self.step + steps:
                raise ReplayError('the target took %d steps from step %d to %d, asked for %d'
                                  % (result.steps_done, self.step, result.step, steps))
            self.step = result.step

    def call(self, command):
        self.forget_echoes()
        if command.service == 'reconfigure':
            config = Config()
            config.deserialize(bytes(command.request))
            self.reconfigure(config)
            return self.echo('reconfigure')
        srv = SERVICES[command.service]
        request = srv._request_class()
        request.deserialize(bytes(command.request))
        answer = self.proxies[command.service](request)
        if not answer.success:
            raise ReplayError('%s refused on replay: %s' % (describe(command), answer.message))
        return self.echo(command.service)


def compare(echo, command):
    """Raises, naming the command and the configuration lines that differ, when the target's state
    before the command is not the recorded one."""
    difference = configuration_difference(echo.configuration, command.configuration)
    if echo.state_hash == command.state_hash and not difference:
        return
    text = 'the state differs before %s: target hash %d, recorded %d' % (
        describe(command), echo.state_hash, command.state_hash)
    if difference:
        text += '; the configuration differs: ' + '; '.join(difference)
    raise ReplayError(text)


def replay(bag_path, source, target_ns):
    commands = read_bag(bag_path, source)
    if not commands:
        raise ReplayError('the bag has no %s/commands message' % source)
    if commands[0].sequence != 0:
        raise ReplayError('the bag starts at command %d, after the node\'s first command: record '
                          'from the start' % commands[0].sequence)
    for expected, command in enumerate(commands):
        if command.sequence != expected:
            raise ReplayError('command %d is missing from the bag' % expected)

    target = Target(target_ns)
    if not target.pause(True).success:
        raise ReplayError('the target refused to pause')
    start = target.reset()
    first = commands[0]
    difference = configuration_difference(start.configuration, first.configuration)
    if difference:
        raise ReplayError('the target is configured differently: ' + '; '.join(difference))
    if start.scene_hash != first.scene_hash:
        raise ReplayError('the target loaded another scene: scene hash %d, recorded %d (same '
                          'configuration, so the particles, colliders or links differ)'
                          % (start.scene_hash, first.scene_hash))
    last_hash = None
    for command in commands:
        target.step_to(command.step)
        if command.service in CHECKPOINTS:
            echo = target.checkpoint()
        elif command.service == 'reset':
            echo = target.reset()
        else:
            echo = target.call(command)
        compare(echo, command)
        last_hash = echo.state_hash
    return len(commands), commands[-1], last_hash, target


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
        count, last, replayed, target = replay(args.bag, args.source.rstrip('/'),
                                               args.target.rstrip('/'))
    except (ReplayError, rospy.ROSException, rospy.ServiceException) as error:
        print('replay failed: %s' % error)
        return 1
    print('replayed %d commands to step %d: state hash %d, recorded %d: match (%d ~step goals '
          'of at most %d steps)' % (count, last.step, replayed, last.state_hash, target.goals,
                                    target.max_steps))
    return 0


if __name__ == '__main__':
    sys.exit(main())
