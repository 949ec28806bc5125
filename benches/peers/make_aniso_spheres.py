#!/usr/bin/env python3
"""Writes AnisoRepresentable.glb (to the path given, default /tmp/AnisoRepresentable.glb): three
anisotropic metal UV spheres (roughness, strength 0.3, 0.3 / 0.5, 0.6 / 0.7, 0.9) whose
KHR_materials_anisotropy alphas Blender's Burley mapping can represent (alpha_t / alpha_b at most
10, which the shared anisotropy models exceed), for the accuracy bench:

    make_aniso_spheres.py /tmp/AnisoRepresentable.glb
    accuracy.py OUT AnisoRepresentable=/tmp/AnisoRepresentable.glb --anisotropy spec
"""
import json
import math
import struct
import sys

import numpy as np

def sphere(nu=96, nv=48):
    P=[];N=[];UV=[];I=[]
    for j in range(nv+1):
        v=j/nv; th=v*math.pi
        for i in range(nu+1):
            u=i/nu; ph=u*2*math.pi
            n=[math.sin(th)*math.cos(ph), math.cos(th), -math.sin(th)*math.sin(ph)]
            P.append(n); N.append(n); UV.append([u, v])
    for j in range(nv):
        for i in range(nu):
            a=j*(nu+1)+i; b=a+1; c=a+nu+1; d=c+1
            I += [a, c, b, b, c, d]
    return np.array(P,np.float32),np.array(N,np.float32),np.array(UV,np.float32),np.array(I,np.uint32)
P,N,UV,I=sphere()
blob=P.tobytes()+N.tobytes()+UV.tobytes()+I.tobytes()
o=[0,len(P.tobytes()),len(P.tobytes())+len(N.tobytes()),len(P.tobytes())+len(N.tobytes())+len(UV.tobytes())]
views=[{"buffer":0,"byteOffset":o[0],"byteLength":P.nbytes},{"buffer":0,"byteOffset":o[1],"byteLength":N.nbytes},
       {"buffer":0,"byteOffset":o[2],"byteLength":UV.nbytes},{"buffer":0,"byteOffset":o[3],"byteLength":I.nbytes}]
acc=[{"bufferView":0,"componentType":5126,"count":len(P),"type":"VEC3","min":P.min(0).tolist(),"max":P.max(0).tolist()},
     {"bufferView":1,"componentType":5126,"count":len(N),"type":"VEC3"},
     {"bufferView":2,"componentType":5126,"count":len(UV),"type":"VEC2"},
     {"bufferView":3,"componentType":5125,"count":len(I),"type":"SCALAR"}]
cases=[(0.3,0.3),(0.5,0.6),(0.7,0.9)]
mats=[{"name":f"r{r}_s{s}","pbrMetallicRoughness":{"baseColorFactor":[0.9,0.9,0.9,1],"metallicFactor":1,"roughnessFactor":r},
       "extensions":{"KHR_materials_anisotropy":{"anisotropyStrength":s}}} for r,s in cases]
meshes=[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3,"material":k}]} for k in range(3)]
nodes=[{"mesh":k,"translation":[2.2*(k-1),0,0]} for k in range(3)]
doc={"asset":{"version":"2.0"},"extensionsUsed":["KHR_materials_anisotropy"],"buffers":[{"byteLength":len(blob)}],
     "bufferViews":views,"accessors":acc,"materials":mats,"meshes":meshes,"nodes":nodes,"scenes":[{"nodes":[0,1,2]}],"scene":0}
js=json.dumps(doc).encode(); js+=b" "*(-len(js)%4); blob+=b"\0"*(-len(blob)%4)
out=struct.pack("<III",0x46546C67,2,12+8+len(js)+8+len(blob))+struct.pack("<II",len(js),0x4E4F534A)+js+struct.pack("<II",len(blob),0x004E4942)+blob
path = sys.argv[1] if len(sys.argv) > 1 else "/tmp/AnisoRepresentable.glb"
open(path, "wb").write(out)
print(path, len(P), "vertices", len(I) // 3, "triangles")
