#!/usr/bin/env python3
"""Writes the body-format seeds of the engine corpus (engine_ops.h reads them): scenes of bodies
of every shape, joints of every kind, requests, queries, sleeping, policies and copies; and, in
the body-force format, the force generators on bodies."""
import math
import os
import struct
import sys

OPS = dict(particle=0, remove_particle=2, spring=3, remove_generator=13, step=15, body=16, remove_body=18, pose=19, velocity=20,
           force=21, torque=22, impulse=23, wake=24, ball=25, hinge=26, fixed=27, distance=28,
           remove_joint=29, motor=30, settings=31, ray=32, overlap=33, collider=34,
           remove_collider=35, particle_contact=36, policy=37, copy=38, point_spring=40,
           body_drag=41, body_buoyancy=42)
BODY_FORMAT, BODY_FORCE_FORMAT = 0xB0, 0xB1


class Seed:
    def __init__(self, format_byte=BODY_FORMAT):
        self.out = bytearray([format_byte])

    def byte(self, b):
        self.out.append(b & 0xFF)

    def u32(self, v):
        self.out += struct.pack('>I', v & 0xFFFFFFFF)

    def real(self, v):
        if float(v * 8).is_integer() and -128 <= v * 8 <= 127:
            self.byte(0)
            self.byte(int(v * 8))
        else:
            self.byte(1)
            self.out += struct.pack('>d', v)

    def vec3(self, v):
        for x in v:
            self.real(x)

    def size(self, v):
        self.byte(1)
        self.byte(max(0, min(255, round(v * 32 - 1))))

    def quat(self, axis=(0, 0, 1), angle=0.0):
        self.byte(1)
        s = math.sin(angle / 2)
        # Modest values only: the reader normalises.
        for x in (math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s):
            self.real(round(x * 8) / 8)

    def material(self, restitution=0.25, friction=0.5):
        self.real(restitution)
        self.real(friction)

    def op(self, name):
        self.byte(OPS[name])

    def known(self, k):  # the k-th id handed out (of a particle, body or joint)
        self.u32((k << 1) | 1)

    def steps(self, n):
        for _ in range(n):
            self.op('step')

    def particle(self, position, radius=0.1):
        self.op('particle')
        self.vec3(position)
        self.vec3((0, 0, 0))
        self.vec3((0, 0, 0))
        self.real(1.0)
        self.real(1.0)
        self.real(radius)

    def plane(self):
        self.op('collider')
        self.byte(0)
        self.vec3((0, 0, 1))
        self.real(0.0)
        self.material()

    def box_collider(self, center, half):
        self.op('collider')
        self.byte(1)
        self.vec3(center)
        for h in half:
            self.size(h)
        self.quat((0, 0, 1), 0.4)
        self.material()

    def body(self, kind, position, shapes, mass=1.0, damping=None, velocity=(0, 0, 0),
             spin=(0, 0, 0)):
        """shapes: [(kind, sizes, local position or None)], kind 0 sphere, 1 box, 2 capsule."""
        self.op('body')
        flags = kind | 4 | (16 if mass else 0) | (32 if damping else 0)
        self.byte(flags)
        self.vec3(position)
        self.quat((1, 0, 0), 0.3)
        self.vec3(velocity)
        self.vec3(spin)
        self.byte(len(shapes))
        for shape, sizes, local in shapes:
            self.byte(shape)
            for s in sizes:
                self.size(s)
            if len(shapes) == 1:
                self.byte(1 if local else 0)
            if len(shapes) > 1 or local:
                self.vec3(local or (0, 0, 0))
                self.quat((0, 1, 0), 0.5)
            self.material()
            self.byte(1)
            self.size(2.0)  # density 500
        if mass:
            self.size(mass)
        if damping:
            self.real(damping[0])
            self.real(damping[1])

    def end_body(self, k, point=(0, 0, 0)):
        self.byte(0)
        self.known(k)
        self.vec3(point)

    def end_particle(self, k):
        self.byte(3)
        self.known(k)

    def end_world(self, point):
        self.byte(4)
        self.vec3(point)


SPHERE, BOX, CAPSULE = 0, 1, 2
DYNAMIC, KINEMATIC, FIXED = 0, 1, 2


def scene(s):
    s.plane()
    s.box_collider((3, 0, 0.5), (1, 1, 0.5))
    s.body(DYNAMIC, (0, 0, 1), [(SPHERE, [0.3], None)])
    s.body(DYNAMIC, (0, 0, 2), [(BOX, [0.3, 0.2, 0.25], None)])
    s.body(DYNAMIC, (3, 0, 2), [(CAPSULE, [0.1, 0.3], (0.1, 0, 0))], damping=(0.5, 0.5))
    s.body(DYNAMIC, (1, 1, 1.5), [(BOX, [0.3, 0.1, 0.1], None), (SPHERE, [0.2], (0.3, 0, 0)),
                                  (CAPSULE, [0.1, 0.2], (-0.3, 0, 0))], mass=0)
    s.body(KINEMATIC, (-1, 0, 0.3), [(BOX, [0.2, 0.2, 0.2], None)], velocity=(0.5, 0, 0))
    s.body(FIXED, (-2, 0, 1), [(BOX, [0.5, 0.5, 0.05], None)])
    s.particle((0, 0, 1.5))
    s.particle((-2, 0, 1.3))


def seeds():
    out = {}
    s = Seed()
    scene(s)
    s.steps(40)
    out['engine_body_seed_scene'] = s

    s = Seed()
    scene(s)
    s.op('ball'); s.end_body(0, (0, 0, 0.3)); s.end_world((0, 0, 2.5)); s.byte(0)
    s.op('hinge'); s.end_body(1); s.end_body(3, (0.3, 0, 0)); s.vec3((0, 1, 0)); s.byte(3)
    s.real(-0.5); s.real(0.5); s.real(2.0); s.real(1.0); s.byte(0)
    s.op('fixed'); s.end_body(2); s.end_body(5); s.byte(0)
    s.op('distance'); s.end_particle(0); s.end_body(1, (0, 0, 0.25)); s.byte(1); s.real(0.5)
    s.byte(0)
    s.op('distance'); s.end_body(3); s.end_world((1, 1, 3)); s.byte(2); s.real(0.5); s.real(2.0)
    s.byte(1)
    s.steps(20)
    s.op('motor'); s.known(1); s.byte(1); s.real(-3.0); s.real(5.0)
    s.steps(10)
    s.op('remove_joint'); s.known(0)
    s.op('remove_body'); s.known(2)
    s.steps(20)
    out['engine_body_seed_joints'] = s

    s = Seed()
    scene(s)
    s.steps(5)
    s.op('force'); s.known(1); s.vec3((0, 5, 0)); s.vec3((0, 0, 2.25))
    s.op('torque'); s.known(3); s.vec3((0, 0, 2))
    s.op('impulse'); s.known(0); s.vec3((1, 0, 0)); s.vec3((0, 0, 1.2)); s.vec3((0, 0.5, 0))
    s.op('pose'); s.known(2); s.vec3((2, 2, 2)); s.quat((0, 0, 1), 1.0)
    s.op('velocity'); s.known(4); s.vec3((0, 0.5, 0)); s.vec3((0, 0, 1))
    s.op('wake'); s.known(1)
    s.steps(10)
    s.op('ray'); s.vec3((-5, 0, 1)); s.vec3((1, 0, 0)); s.real(20.0)
    s.op('ray'); s.vec3((0, 0, 5)); s.vec3((0, 0, -1)); s.real(10.0)
    s.op('overlap'); s.vec3((0, 0, 1)); s.byte(0); s.size(1.0)
    s.op('overlap'); s.vec3((1, 1, 1)); s.byte(1); s.size(1.0); s.size(0.5); s.size(2.0)
    s.quat((1, 0, 0), 0.7)
    s.op('particle_contact'); s.byte(0); s.byte(1)
    s.op('particle_contact'); s.byte(1); s.known(0); s.material(0.0, 0.8)
    s.steps(10)
    s.op('remove_collider'); s.u32(2)
    s.steps(10)
    out['engine_body_seed_requests'] = s

    s = Seed()
    scene(s)
    s.op('settings'); s.u32((1 << 0) | (1 << 1) | (1 << 12) | (1 << 13)); s.byte(2); s.byte(3)
    s.size(1.0); s.size(0.5)
    s.steps(30)
    s.op('copy')
    s.op('impulse'); s.known(1); s.vec3((0, 0, 2)); s.vec3((0, 0, 2)); s.vec3((0, 0, 0))
    s.steps(5)
    s.op('copy')
    out['engine_body_seed_sleep'] = s

    s = Seed()
    scene(s)
    s.op('policy'); s.byte(5)  # kReset, with a snapshot
    s.steps(5)
    s.op('velocity'); s.known(0); s.vec3((1e5, 0, 0)); s.vec3((0, 0, 0))
    s.steps(3)
    s.op('copy')
    s.op('policy'); s.byte(1)  # kPause
    s.op('velocity'); s.known(1); s.vec3((0, 0, 2e4)); s.vec3((0, 0, 0))
    s.steps(3)
    s.op('policy'); s.byte(8)  # kReset again, resumed
    s.steps(2)
    s.op('policy'); s.byte(15)  # clear()
    s.steps(2)
    out['engine_body_seed_policies'] = s

    s = Seed(BODY_FORCE_FORMAT)
    scene(s)
    s.op('point_spring'); s.end_body(1, (0.3, 0, 0)); s.end_world((0, 0, 4)); s.real(20.0)
    s.real(1.0); s.real(0.5); s.byte(0)
    s.op('point_spring'); s.end_body(0); s.end_particle(0); s.real(10.0); s.real(-1.0); s.real(0.0)
    s.byte(1)
    s.op('point_spring'); s.end_body(0); s.end_body(2, (0, 0, 0.1)); s.real(5.0); s.real(0.5)
    s.real(0.25); s.byte(0)
    s.op('body_drag'); s.known(2); s.real(0.5); s.real(0.125); s.real(0.25)
    s.op('body_buoyancy'); s.known(3); s.real(-1.0); s.real(0.0); s.real(1000.0); s.real(0.5)
    s.vec3((0, 0, 1))
    s.steps(30)
    s.op('copy')
    s.op('remove_generator'); s.u32(1)
    s.op('remove_particle'); s.known(0)
    s.steps(10)
    s.op('remove_body'); s.known(0)
    s.steps(20)
    out['engine_body_seed_forces'] = s
    return out


if __name__ == '__main__':
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__),
                                                                'engine_corpus')
    for name, seed in seeds().items():
        with open(os.path.join(folder, name), 'wb') as f:
            f.write(bytes(seed.out))
