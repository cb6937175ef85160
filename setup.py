# The Python package enhanced_orb (python/enhanced_orb), installed by catkin_python_setup(); the
# compiled half, _enhanced_orb, is built and installed by CMakeLists.txt beside it.
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=["enhanced_orb"], package_dir={"": "python"}))
