"""Message classes (as rosidl_generator_py's behave) and node parameters; exits 0."""

import array

import rclpy
from rclpy.node import Node
from rclpy.node import ParameterNotDeclaredException
from rclpy.parameter import Parameter
from rclpy.parameter import SetParametersResult

from demo_interfaces.msg import Chatter, Frame, Sample
from std_msgs.msg import String


def expect_assertion(make, text):
    try:
        make()
    except AssertionError as e:
        assert text in str(e), str(e)
    else:
        raise SystemExit('no AssertionError for ' + text)


rclpy.init(args=['messages.py', '--ros-args', '-p', 'rate:=2.5', '-p', 'py_messages:label:=hi',
                 '-p', 'other:label:=no', '-r', '__ns:=/checks'])
node = Node('py_messages')
assert node.get_fully_qualified_name() == '/checks/py_messages', node.get_fully_qualified_name()
# parameters: overrides from -p, defaults, callbacks that may refuse
assert node.declare_parameter('rate', 1.0).value == 2.5
assert node.declare_parameter('label', 'x').value == 'hi'
assert node.declare_parameter('count', 3).type_ == Parameter.Type.INTEGER
node.add_on_set_parameters_callback(
    lambda ps: SetParametersResult(successful=all(p.value != 13 for p in ps),
                                   reason='13 is unlucky'))
results = node.set_parameters([Parameter('count', value=4), Parameter('count', value=13)])
assert [r.successful for r in results] == [True, False] and results[1].reason == '13 is unlucky'
assert node.get_parameter('count').value == 4
try:
    node.get_parameter('nope')
except ParameterNotDeclaredException:
    pass
else:
    raise SystemExit('an undeclared parameter must raise')
# Node options: constructor overrides win over -p and are declared with
# automatically_declare_parameters_from_overrides; undeclared ones may be set
# with allow_undeclared_parameters
loose = Node('py_loose', parameter_overrides=[Parameter('rate', value=9.5),
                                              Parameter('mode', value='fast')],
             automatically_declare_parameters_from_overrides=True,
             allow_undeclared_parameters=True)
assert loose.get_parameter('rate').value == 9.5 and loose.get_parameter('mode').value == 'fast'
assert loose.get_parameter('unset').type_ == Parameter.Type.NOT_SET
assert loose.set_parameters([Parameter('speed', value=3)])[0].successful
assert loose.has_parameter('speed') and loose.get_parameter('speed').value == 3
loose.destroy_node()
chatter = Chatter(data='hi', count=3)
assert chatter == Chatter(data='hi', count=3)
assert chatter != Chatter(data='hi', count=4)
assert repr(chatter) == "demo_interfaces.msg.Chatter(data='hi', count=3)", repr(chatter)
assert Chatter().data == '' and Chatter().count == 0
assert Chatter.get_fields_and_field_types() == {'data': 'string', 'count': 'uint32'}
assert Frame.get_fields_and_field_types()['data'] == 'sequence<uint8>'
assert isinstance(Frame().data, array.array) and Frame().data.typecode == 'B'
assert Sample().sine == 0.0 and String(data='x').data == 'x'
expect_assertion(lambda: Chatter(data=3), "The 'data' field must be of type 'str'")
expect_assertion(lambda: Chatter(count=-1), "The 'count' field must be an unsigned integer in "
                                            '[0, 4294967295]')
expect_assertion(lambda: Sample(sine=1), "The 'sine' field must be of type 'float'")
expect_assertion(lambda: Chatter(nope=1), 'Invalid arguments passed to constructor: nope')
try:
    from demo_interfaces.msg import Missing  # noqa: F401
except ImportError as e:
    assert 'Missing' in str(e), str(e)
else:
    raise SystemExit('importing a message that is not described must fail')
# a message through the bus and back, in this process: CDR both ways (cdr.mjs)
got = []
node.create_subscription(Frame, 'frames', got.append, 10)
publisher = node.create_publisher(Frame, 'frames', 10)
sent = Frame(height=2, width=1, encoding='mono8', step=1, data=array.array('B', [7, 255]))
try:
    publisher.publish(Chatter())
except TypeError as e:
    assert 'Expected' in str(e), str(e)
else:
    raise SystemExit('publishing a message of another type must fail')
publisher.publish(sent)
for _ in range(50):
    if got:
        break
    rclpy.spin_once(node, timeout_sec=0.1)
assert got == [sent], got
node.get_logger().info('message classes behave')
rclpy.shutdown()
