from setuptools import Extension
from setuptools import setup

package_name = 'py_native'

setup(
    name=package_name,
    version='0.1.0',
    packages=[package_name],
    ext_modules=[Extension('py_native._speedups', ['src/speedups.c'])],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    zip_safe=False,
    description='A C extension module',
    license='Apache-2.0',
)
