#!/usr/bin/env python3
"""Writes a small ONNX network in YOLOX's output layout whose output is known from its weights
(tests/features/dnn_detector_test.cc).

    make_yolox_onnx.py OUT.onnx

The network takes a 1 x 3 x H x W image (BGR, 0-255, H and W multiples of 32) and gives
1 x N x 85: three heads, convolutions of kernel and stride 8, 16 and 32, their outputs
flattened and concatenated in that order as YOLOX's raw head is. Only the stride-8 head sees
anything: a cell's objectness is the mean of its 8 x 8 patch / 255 (1 on a white block, 0 on
black), its class-0 score 1, its box centred on the cell ((x + 0.5, y + 0.5) x 8) and 16 x 16
px (log 2 per side). The other heads' objectness is 0.
"""
import math
import sys

import numpy
import onnx
from onnx import TensorProto, helper, numpy_helper


def head(name, stride, active):
    weights = numpy.zeros((85, 3, stride, stride), dtype=numpy.float32)
    biases = numpy.zeros(85, dtype=numpy.float32)
    if active:
        weights[4] = 1.0 / (stride * stride * 3 * 255.0)
        biases[0:2] = 0.5
        biases[2:4] = math.log(2.0)
        biases[5] = 1.0
    initialisers = [numpy_helper.from_array(weights, name + "_w"),
                    numpy_helper.from_array(biases, name + "_b")]
    nodes = [
        helper.make_node("Conv", ["images", name + "_w", name + "_b"], [name + "_conv"],
                         kernel_shape=[stride, stride], strides=[stride, stride]),
        helper.make_node("Reshape", [name + "_conv", "flat_shape"], [name + "_flat"]),
    ]
    return nodes, initialisers


def main():
    if len(sys.argv) != 2:
        print("usage: make_yolox_onnx.py OUT.onnx", file=sys.stderr)
        return 2
    nodes, initialisers = [], [numpy_helper.from_array(numpy.array([1, 85, -1], dtype=numpy.int64),
                                                        "flat_shape")]
    for stride in (8, 16, 32):
        head_nodes, head_initialisers = head("s%d" % stride, stride, stride == 8)
        nodes += head_nodes
        initialisers += head_initialisers
    nodes.append(helper.make_node("Concat", ["s8_flat", "s16_flat", "s32_flat"], ["all"], axis=2))
    nodes.append(helper.make_node("Transpose", ["all"], ["output"], perm=[0, 2, 1]))
    graph = helper.make_graph(
        nodes, "yolox_like",
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, [1, 3, "height", "width"])],
        [helper.make_tensor_value_info("output", TensorProto.FLOAT, [1, "cells", 85])],
        initialisers)
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)])
    model.ir_version = 6
    onnx.checker.check_model(model)
    onnx.save(model, sys.argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main())
