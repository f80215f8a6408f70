// Shaders of the -bsp samples. Texture sizes are given with q3map_textureSize, so the samples
// need no images and their texture coordinates do not depend on any game data.

textures/samples/wall
{
	q3map_textureSize 128 128
}

textures/samples/floor
{
	q3map_textureSize 64 64
}

textures/samples/trim
{
	q3map_textureSize 256 32
}

textures/samples/sky
{
	q3map_textureSize 128 128
	surfaceparm sky
	surfaceparm noimpact
	surfaceparm nolightmap
	q3map_sun 1 1 1 100 45 60
	q3map_surfacelight 50
}

textures/samples/water
{
	q3map_textureSize 64 64
	surfaceparm trans
	surfaceparm nonsolid
	surfaceparm water
	surfaceparm nolightmap
}

textures/samples/fog
{
	q3map_textureSize 64 64
	surfaceparm trans
	surfaceparm nonsolid
	surfaceparm fog
	surfaceparm nolightmap
	fogparms ( 0.5 0.5 0.6 ) 512
}

textures/samples/lava
{
	q3map_textureSize 64 64
	tessSize 64
	surfaceparm trans
	surfaceparm nonsolid
	surfaceparm lava
	surfaceparm nolightmap
}

textures/common/caulk
{
	surfaceparm nodraw
	surfaceparm nolightmap
	surfaceparm nomarks
}

textures/common/hint
{
	surfaceparm nodraw
	surfaceparm nonsolid
	surfaceparm structural
	surfaceparm trans
	surfaceparm noimpact
	surfaceparm hint
}

textures/common/skip
{
	surfaceparm nodraw
	surfaceparm nonsolid
	surfaceparm structural
	surfaceparm trans
	surfaceparm noimpact
	surfaceparm skip
}

textures/common/areaportal
{
	surfaceparm nodraw
	surfaceparm nolightmap
	surfaceparm nonsolid
	surfaceparm structural
	surfaceparm trans
	surfaceparm nomarks
	surfaceparm areaportal
}

textures/common/origin
{
	surfaceparm nodraw
	surfaceparm nolightmap
	surfaceparm nonsolid
	surfaceparm trans
	surfaceparm origin
}

textures/common/clip
{
	surfaceparm nodraw
	surfaceparm nolightmap
	surfaceparm nonsolid
	surfaceparm trans
	surfaceparm nomarks
	surfaceparm noimpact
	surfaceparm playerclip
}

textures/samples/cloned
{
	q3map_textureSize 128 128
	q3map_cloneShader textures/samples/clonecopy
}

textures/samples/clonecopy
{
	q3map_textureSize 128 128
	surfaceparm nolightmap
}

textures/samples/backed
{
	q3map_textureSize 128 128
	q3map_backShader textures/samples/backcopy
}

textures/samples/backcopy
{
	q3map_textureSize 64 64
	surfaceparm nolightmap
}

textures/samples/remapped
{
	q3map_textureSize 128 128
	q3map_remapShader textures/samples/remaptarget
}

textures/samples/remaptarget
{
	q3map_textureSize 128 128
	surfaceparm nomarks
}

textures/samples/tcmodded
{
	q3map_textureSize 128 128
	q3map_tcMod scale 2 0.5
	q3map_tcMod rotate 30
	q3map_tcMod translate 0.25 0.5
}

textures/samples/cel
{
	q3map_textureSize 32 32
	surfaceparm nolightmap
}

textures/samples/decal
{
	q3map_textureSize 64 64
	surfaceparm nonsolid
	surfaceparm trans
	surfaceparm nomarks
	polygonOffset
	{
		map textures/samples/decal.tga
		blendFunc GL_DST_COLOR GL_ZERO
		alphaGen vertex
	}
}

textures/samples/grass
{
	q3map_textureSize 64 64
	q3map_foliage models/samples/post.md3 0.5 64 0.5 2
}

// color_mods: vertex colour and alpha steps, applied in script order
textures/samples/rgbdot
{
	q3map_textureSize 64 64
	q3map_rgbGen dotProduct ( 0.3 0.5 0.8 )
	q3map_alphaMod dotProduct2 ( 0 0.6 0.8 )
}

textures/samples/colorconst
{
	q3map_textureSize 64 64
	q3map_colorGen const ( 0.2 0.4 0.6 )
	q3map_alphaGen const 0.3
	q3map_alphaMod scale 0.5
}

textures/samples/dotscale
{
	q3map_textureSize 64 64
	q3map_rgbMod dotProductScale ( 1 0 0 -1 1 )
	q3map_alphaMod dotProduct2scale ( 0 1 0 0.25 1 )
	q3map_colorMod scale ( 1 0.5 0.25 )
}

textures/samples/slopealpha
{
	q3map_textureSize 64 64
	q3map_nonplanar
	q3map_shadeAngle 180
	q3map_alphaMod dotproduct2 ( 0.0 0.0 0.95 )
}

textures/samples/alphavolume
{
	q3map_alphaMod volume
	q3map_alphaMod set 0.5
	surfaceparm nodraw
	surfaceparm nonsolid
	surfaceparm trans
}

textures/samples/tintvolume
{
	q3map_colorMod volume
	q3map_rgbMod scale ( 0.5 1 0.25 )
	surfaceparm nodraw
	surfaceparm nonsolid
	surfaceparm trans
}

textures/samples/terrain
{
	q3map_terrain
	q3map_textureSize 128 128
	surfaceparm nodraw
	surfaceparm nolightmap
}

textures/samples/terrain_0
{
	q3map_textureSize 64 64
}

textures/samples/terrain_1
{
	q3map_textureSize 64 64
}

textures/samples/terrain_2
{
	q3map_textureSize 64 64
	q3map_tcGen ivector ( 256 0 0 ) ( 0 256 0 )
}

textures/samples/terrain_0to1
{
	q3map_textureSize 64 64
}

textures/samples/terrain_1to2
{
	q3map_textureSize 64 64
}

// model_forcemeta: model surfaces under this shader join the meta pipeline even without -meta
textures/samples/forcemeta
{
	q3map_textureSize 64 64
	q3map_forceMeta
}
