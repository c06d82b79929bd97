#!/usr/bin/env python3
"""A bad scene or parameter stops the node at start, naming the key and the reason
(rostest: test/bad_scene.test)."""
import os
import subprocess
import sys
import unittest

import rospy
import rostest


class BadSceneTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('bad_scene_test')

    def start(self, name, params):
        for key, value in params.items():
            rospy.set_param('/%s/%s' % (name, key), value)
        env = dict(os.environ)
        env['PATH'] = '/usr/bin:' + env.get('PATH', '')
        result = subprocess.run(['rosrun', 'mass_aggregate_sim', 'node', '__name:=' + name],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                timeout=30, env=env)
        return result.returncode, result.stdout

    def test_bad_mass_names_the_key(self):
        code, output = self.start('bad_mass', {'scene': {
            'particles': [{'name': 'a', 'position': [0, 0, 1], 'mass': -2.0}]}})
        self.assertEqual(code, 1, output)
        self.assertIn('scene.particles[0].mass: must be > 0', output)

    def test_misspelt_key_is_refused(self):
        code, output = self.start('misspelt', {'scene': {'gravty': [0, 0, -9.81]}})
        self.assertEqual(code, 1, output)
        self.assertIn('scene.gravty: unknown key', output)

    def test_unknown_link_particle(self):
        code, output = self.start('bad_link', {'scene': {
            'particles': [{'name': 'a', 'position': [0, 0, 1]}],
            'links': [{'type': 'spring', 'a': 'a', 'b': 'nobody', 'stiffness': 1.0}]}})
        self.assertEqual(code, 1, output)
        self.assertIn("scene.links[0]: b: no particle named 'nobody'", output)

    def test_bad_parameter(self):
        code, output = self.start('bad_integrator', {'integrator': 'leapfrog'})
        self.assertEqual(code, 1, output)
        self.assertIn("~integrator: unknown integrator 'leapfrog'", output)


if __name__ == '__main__':
    rostest.rosrun('mass_aggregate_sim', 'bad_scene', BadSceneTest, sys.argv)
