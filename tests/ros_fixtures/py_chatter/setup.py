from glob import glob

from setuptools import setup

package_name = 'py_chatter'

setup(
    name=package_name,
    version='0.2.0',
    packages=[package_name],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/launch', glob('launch/*.launch.xml')),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    description='Python nodes of demo_interfaces/msg/Chatter',
    license='Apache-2.0',
    entry_points={
        'console_scripts': [
            'talker = py_chatter.talker:main',
            'listener = py_chatter.listener:main',
            'crasher = py_chatter.crasher:main',
        ],
    },
)
